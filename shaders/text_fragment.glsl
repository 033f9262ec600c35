// Text: the atlas holds stb_truetype's coverage, used as the alpha of the text colour.
#version 330 core
in vec2 v_uv;
in vec4 v_color;
uniform sampler2D atlas;
out vec4 frag_color;
void main() {
  frag_color = vec4(v_color.rgb, v_color.a * texture(atlas, v_uv).r);
}
