// The opaque fills (the body's triangles, the planes, the panel's backdrop): the vertex
// colour and nothing else. Kept apart from shape_fragment.glsl because the fills cover
// most of the frame and a software rasterizer runs every instruction of a shader for every
// pixel (llvmpipe evaluates both sides of a branch): this shader makes a 720p live frame
// ~3.5 ms cheaper under llvmpipe than the stroke-and-hatch one would.
#version 330 core
in vec4 v_color;
out vec4 frag_color;
void main() {
  frag_color = v_color;
}
