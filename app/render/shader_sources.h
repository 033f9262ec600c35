// The GLSL sources of shaders/*.glsl, embedded into the binary at build time (the
// assembler's .incbin, see shader_sources.cpp), so the executable finds its shaders from
// any working directory and needs no files installed next to it.
#pragma once

#include <string>

namespace invfree::render {

struct ShaderSources {
  const char* shape_vertex;
  const char* shape_fragment;
  const char* fill_fragment;  // with shape_vertex
  const char* text_vertex;
  const char* text_fragment;
};

const ShaderSources& shader_sources();

// The source to compile in the current context. shaders/*.glsl are written for desktop
// OpenGL 3.3 (first directive `#version 330 core`); for an OpenGL ES 3.0 context (WebGL 2
// in the web build) that line becomes `#version 300 es` with default precisions, the
// rest unchanged (GLSL ES 3.00 accepts the same `in`/`out`/`layout` syntax). Desktop: the
// source as it is.
std::string glsl_for_context(const char* source, bool opengl_es);

}  // namespace invfree::render
