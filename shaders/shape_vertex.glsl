// Flat-coloured geometry (the body's triangles, edges, planes, colour bar) in pixel
// coordinates: x right, y down, origin at the frame's top-left corner. `stroke` carries a
// stroke's antialiasing: (signed distance from its centre line, half width), both in
// pixels; half width <= 0 means a plain fill.
#version 330 core
layout(location = 0) in vec2 position_px;
layout(location = 1) in vec4 color;
layout(location = 2) in vec2 stroke;
uniform vec2 frame_size;
out vec4 v_color;
out vec2 v_stroke;
void main() {
  v_color = color;
  v_stroke = stroke;
  gl_Position = vec4(2.0 * position_px.x / frame_size.x - 1.0, 1.0 - 2.0 * position_px.y / frame_size.y, 0.0, 1.0);
}
