// A context's get-proc-address function, the one thing a context hands the renderer
// (OSMesaGetProcAddress and glfwGetProcAddress both have this type). Kept apart from
// gl_api.h so that code including another GL header (GL/osmesa.h, GLFW) need not also
// include GL/glcorearb.h.
#pragma once

namespace invfree::render {

using GlProc = void (*)();
using GlGetProcAddress = GlProc (*)(const char* name);

}  // namespace invfree::render
