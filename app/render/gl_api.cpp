#include "app/render/gl_api.h"

#include <cstdio>
#include <cstring>

namespace invfree::render {

std::string load_gl_api(GlGetProcAddress get_proc_address, GlApi* api) {
  GlApi loaded;
#define INVFREE_GL_LOAD(type, name)                                   \
  loaded.name = reinterpret_cast<type>(get_proc_address("gl" #name)); \
  if (loaded.name == nullptr) return "OpenGL function gl" #name " is not available";
  INVFREE_GL_FUNCTIONS(INVFREE_GL_LOAD)
#undef INVFREE_GL_LOAD
  // Every pointer exists even for a too-old context (Mesa hands out stubs), so check the
  // version the context really provides.
  const auto* version = reinterpret_cast<const char*>(loaded.GetString(GL_VERSION));
  int major = 0, minor = 0;
  // "OpenGL ES 3.0 ..." for an ES context (WebGL 2 reports "OpenGL ES 3.0 (WebGL 2.0 ...)").
  loaded.opengl_es = version != nullptr && std::strncmp(version, "OpenGL ES ", 10) == 0;
  const char* number = loaded.opengl_es ? version + 10 : version;
  if (version == nullptr || std::sscanf(number, "%d.%d", &major, &minor) != 2)
    return "no current OpenGL context (glGetString(GL_VERSION) failed)";
  if (loaded.opengl_es ? major < 3 : (major < 3 || (major == 3 && minor < 3)))
    return std::string("OpenGL 3.3 or OpenGL ES 3.0 or newer is needed, the context provides ") +
           version;
  *api = loaded;
  return "";
}

}  // namespace invfree::render
