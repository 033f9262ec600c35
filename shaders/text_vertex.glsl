// Glyph quads in pixel coordinates (x right, y down) with atlas texel coordinates.
#version 330 core
layout(location = 0) in vec2 position_px;
layout(location = 1) in vec2 texel;
layout(location = 2) in vec4 color;
uniform vec2 frame_size;
uniform vec2 atlas_size;
out vec2 v_uv;
out vec4 v_color;
void main() {
  v_uv = texel / atlas_size;
  v_color = color;
  gl_Position = vec4(2.0 * position_px.x / frame_size.x - 1.0, 1.0 - 2.0 * position_px.y / frame_size.y, 0.0, 1.0);
}
