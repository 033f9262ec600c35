// The GLSL sources of shaders/*.glsl, embedded into the binary at build time (the
// assembler's .incbin, see shader_sources.cpp), so the executable finds its shaders from
// any working directory and needs no files installed next to it.
#pragma once

namespace invfree::render {

struct ShaderSources {
  const char* shape_vertex;
  const char* shape_fragment;
  const char* fill_fragment;  // with shape_vertex
  const char* text_vertex;
  const char* text_fragment;
};

const ShaderSources& shader_sources();

}  // namespace invfree::render
