#include "app/render/shader_sources.h"

#include "app/embed_section.h"

// Each file is placed in .rodata followed by a NUL, so it is a C string. INVFREE_SHADER_DIR
// (the source tree's shaders/, absolute) comes from app/render/CMakeLists.txt, which also
// makes this file depend on the .glsl files so an edited shader is re-embedded.
#define INVFREE_EMBED(symbol, file)                                                              \
  asm(INVFREE_RODATA_OPEN(symbol) ".globl " #symbol "\n" #symbol                                 \
                                  ":\n"                                                          \
                                  ".incbin \"" INVFREE_SHADER_DIR "/" file                       \
                                  "\"\n"                                                         \
                                  ".byte 0\n" INVFREE_RODATA_SIZE(symbol) INVFREE_RODATA_CLOSE); \
  extern "C" const char symbol[];

INVFREE_EMBED(invfree_shape_vertex_glsl, "shape_vertex.glsl")
INVFREE_EMBED(invfree_shape_fragment_glsl, "shape_fragment.glsl")
INVFREE_EMBED(invfree_fill_fragment_glsl, "fill_fragment.glsl")
INVFREE_EMBED(invfree_text_vertex_glsl, "text_vertex.glsl")
INVFREE_EMBED(invfree_text_fragment_glsl, "text_fragment.glsl")

namespace invfree::render {

const ShaderSources& shader_sources() {
  static const ShaderSources sources{invfree_shape_vertex_glsl, invfree_shape_fragment_glsl,
                                     invfree_fill_fragment_glsl, invfree_text_vertex_glsl,
                                     invfree_text_fragment_glsl};
  return sources;
}

std::string glsl_for_context(const char* source, bool opengl_es) {
  std::string text(source);
  if (!opengl_es) return text;
  const std::string desktop = "#version 330 core\n";
  const size_t at = text.find(desktop);
  if (at == std::string::npos) return text;  // the compiler then names the missing line
  // The version directive must come first; the comments before it move after it.
  return "#version 300 es\nprecision highp float;\nprecision highp int;\n" +
         text.erase(at, desktop.size());
}

}  // namespace invfree::render
