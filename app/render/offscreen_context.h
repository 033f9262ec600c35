// An OpenGL context with no display at all (no X server, no DISPLAY): Mesa's OSMesa
// (llvmpipe, software), OpenGL 3.3+ core profile, made current on the calling thread.
// The renderer draws into its own framebuffer objects, so the context's own buffer is a
// token 1x1 one.
//
// libOSMesa is opened with dlopen(RTLD_LOCAL) rather than linked: its gl* symbols then
// never enter the process's global symbol scope, so the same executable can also link
// libGL for the live window (GLFW, ImGui's OpenGL2 backend) without either library's gl*
// shadowing the other's. The renderer reaches OSMesa's GL through OSMesaGetProcAddress
// (see gl_api.h). Only the headers of libosmesa6-dev are used at build time.
#pragma once

#include <memory>
#include <string>

#include "app/render/gl_proc.h"

namespace invfree::render {

class OffscreenContext {
 public:
  // Creates the context and makes it current on this thread. On failure returns null and
  // sets *error to one line (e.g. libOSMesa missing: which package to install).
  static std::unique_ptr<OffscreenContext> create(std::string* error);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  // OSMesaGetProcAddress, for load_gl_api.
  GlGetProcAddress get_proc_address() const { return get_proc_address_; }
  // Makes the context current on the calling thread again (e.g. after another context).
  bool make_current();

 private:
  OffscreenContext() = default;
  void* library_ = nullptr;  // dlopen handle
  void* context_ = nullptr;  // OSMesaContext
  GlGetProcAddress get_proc_address_ = nullptr;
  unsigned char buffer_[4] = {};
  using MakeCurrentFn = unsigned char (*)(void*, void*, unsigned, int, int);
  using DestroyFn = void (*)(void*);
  MakeCurrentFn make_current_ = nullptr;
  DestroyFn destroy_ = nullptr;
};

}  // namespace invfree::render
