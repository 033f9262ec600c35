// The vertex colour, with two optional effects:
//  - strokes are antialiased analytically: coverage = how much of the pixel lies within
//    the half width of the centre line (a one-pixel ramp), so edges are smooth without
//    multisampling and look the same on every OpenGL implementation;
//  - diagonal hatching (the ground and ceiling half-planes: the engineering symbol of a
//    rigid support). hatch = (spacing px, line width px, strength 0..1, unused); the
//    stripes are antialiased the same way, by their distance to the pixel centre.
#version 330 core
in vec4 v_color;
in vec2 v_stroke;
uniform vec4 hatch;
uniform vec4 hatch_color;
out vec4 frag_color;
void main() {
  vec4 c = v_color;
  if (v_stroke.y > 0.0) c.a *= clamp(v_stroke.y - abs(v_stroke.x) + 0.5, 0.0, 1.0);
  if (hatch.z > 0.0) {
    float s = hatch.x;
    float d = mod(gl_FragCoord.x + gl_FragCoord.y, s);
    float dist = min(d, s - d) * 0.70710678;  // distance to the nearest stripe's centre line
    float cover = clamp(0.5 * hatch.y - dist + 0.5, 0.0, 1.0) * hatch.z;
    c.rgb = mix(c.rgb, hatch_color.rgb, cover * hatch_color.a);
  }
  frag_color = c;
}
