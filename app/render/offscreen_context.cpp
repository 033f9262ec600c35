#include "app/render/offscreen_context.h"

#include <GL/osmesa.h>
#include <dlfcn.h>

namespace invfree::render {

namespace {

// Debian 12's libosmesa6 ships libOSMesa.so.8; the unversioned name (from the -dev
// package) is the fallback for other layouts.
constexpr const char* kLibraryNames[] = {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"};

template <class F>
F symbol(void* library, const char* name) {
  return reinterpret_cast<F>(dlsym(library, name));
}

}  // namespace

std::unique_ptr<OffscreenContext> OffscreenContext::create(std::string* error) {
  std::unique_ptr<OffscreenContext> c(new OffscreenContext());
  for (const char* name : kLibraryNames) {
    c->library_ = dlopen(name, RTLD_NOW | RTLD_LOCAL);
    if (c->library_ != nullptr) break;
  }
  if (c->library_ == nullptr) {
    *error =
        "cannot load libOSMesa.so.8 for offscreen rendering (install libosmesa6: sudo "
        "scripts/install-deps.sh)";
    return nullptr;
  }
  const auto create_attribs =
      symbol<decltype(&OSMesaCreateContextAttribs)>(c->library_, "OSMesaCreateContextAttribs");
  c->make_current_ = symbol<MakeCurrentFn>(c->library_, "OSMesaMakeCurrent");
  c->destroy_ = symbol<DestroyFn>(c->library_, "OSMesaDestroyContext");
  c->get_proc_address_ = symbol<GlGetProcAddress>(c->library_, "OSMesaGetProcAddress");
  if (!create_attribs || !c->make_current_ || !c->destroy_ || !c->get_proc_address_) {
    *error = "libOSMesa lacks OSMesaCreateContextAttribs (Mesa 11.2 or newer is needed)";
    return nullptr;
  }
  // Core profile 3.3; no depth, stencil or accumulation buffer (the renderer's FBOs have
  // what they need).
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_STENCIL_BITS,
                         0,
                         OSMESA_ACCUM_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         3,
                         0};
  c->context_ = create_attribs(attribs, nullptr);
  if (c->context_ == nullptr) {
    *error = "OSMesa could not create an OpenGL 3.3 core context";
    return nullptr;
  }
  if (!c->make_current()) {
    *error = "OSMesaMakeCurrent failed";
    return nullptr;
  }
  return c;
}

bool OffscreenContext::make_current() {
  return make_current_(context_, buffer_, GL_UNSIGNED_BYTE, 1, 1) != 0;
}

OffscreenContext::~OffscreenContext() {
  if (context_ != nullptr) destroy_(context_);
  // The library stays loaded: llvmpipe's worker threads and atexit handlers may still
  // refer to it, and unloading it buys nothing in a process that is about to end.
}

}  // namespace invfree::render
