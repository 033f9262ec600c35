#include "app/render/shader_sources.h"

// Each file is placed in .rodata followed by a NUL, so it is a C string. INVFREE_SHADER_DIR
// (the source tree's shaders/, absolute) comes from app/render/CMakeLists.txt, which also
// makes this file depend on the .glsl files so an edited shader is re-embedded.
#define INVFREE_EMBED(symbol, file)            \
  asm(".pushsection .rodata\n"                 \
      ".globl " #symbol "\n" #symbol           \
      ":\n"                                    \
      ".incbin \"" INVFREE_SHADER_DIR "/" file \
      "\"\n"                                   \
      ".byte 0\n"                              \
      ".popsection\n");                        \
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

}  // namespace invfree::render
