// The OpenGL functions the renderer uses, as a table of function pointers filled by a
// loader from any context's get-proc-address function: OSMesaGetProcAddress offscreen,
// glfwGetProcAddress in the live window.
//
// Why a table and not the gl* symbols: libOSMesa and libGL both export every gl* symbol,
// so which one a direct call reaches would depend on link order, and the live mode (GLFW
// + ImGui's OpenGL2 backend, which calls gl* directly through libGL) and the offscreen
// renderer (OSMesa) live in one executable. The renderer therefore never references a
// gl* symbol: it calls only through this table, loaded from whichever context is current,
// and the offscreen context dlopens libOSMesa privately (see offscreen_context.h).
//
// Needs an OpenGL 3.3 context, core or compatibility profile, or OpenGL ES 3.0 (WebGL 2:
// the functions above are all in ES 3.0, and the shaders are switched to GLSL ES, see
// shader_sources.h).
#pragma once

#include <GL/glcorearb.h>

#include <string>

#include "app/render/gl_proc.h"

namespace invfree::render {

// X(type, name): the function gl<name> of pointer type <type>.
#define INVFREE_GL_FUNCTIONS(X)                                              \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                   \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                     \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                         \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                               \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                             \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                       \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                               \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                           \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                               \
  X(PFNGLBUFFERDATAPROC, BufferData)                                         \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                 \
  X(PFNGLCLEARPROC, Clear)                                                   \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                         \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                   \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                   \
  X(PFNGLCREATESHADERPROC, CreateShader)                                     \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                   \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                         \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                   \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                       \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                     \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                 \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                         \
  X(PFNGLDISABLEPROC, Disable)                                               \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                         \
  X(PFNGLENABLEPROC, Enable)                                                 \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)               \
  X(PFNGLFINISHPROC, Finish)                                                 \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)               \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                     \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                         \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                               \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                             \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                       \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                               \
  X(PFNGLGETERRORPROC, GetError)                                             \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                       \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                           \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                     \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                             \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                       \
  X(PFNGLGETSTRINGPROC, GetString)                                           \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                         \
  X(PFNGLISENABLEDPROC, IsEnabled)                                           \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                       \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                       \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                                         \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                         \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                       \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample) \
  X(PFNGLSCISSORPROC, Scissor)                                               \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                     \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                         \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                   \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                           \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                           \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                                           \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                         \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                       \
  X(PFNGLVIEWPORTPROC, Viewport)

struct GlApi {
#define INVFREE_GL_MEMBER(type, name) type name = nullptr;
  INVFREE_GL_FUNCTIONS(INVFREE_GL_MEMBER)
#undef INVFREE_GL_MEMBER
  bool opengl_es = false;  // an OpenGL ES 3.x context (WebGL 2 in the web build)
};

// Fills `api` from the current context. Returns "" or a one-line error naming the first
// missing function or the too-old GL version.
std::string load_gl_api(GlGetProcAddress get_proc_address, GlApi* api);

}  // namespace invfree::render
