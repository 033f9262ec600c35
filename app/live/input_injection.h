// A test's scripted input (Injection, live_app.h) written into ImGui's io in place of
// GLFW's, between the backends' NewFrame and ImGui::NewFrame: the panel and the picture
// then see exactly what a person's mouse and keyboard would do. A key held in one
// injection and absent from the next is released, so listing it in one frame is one press.
#pragma once

#include <vector>

#include "app/live/live_app.h"

namespace invfree::live {

class InputInjection {
 public:
  void apply(const Injection& inject);

 private:
  std::vector<int> held_keys_;  // held by the last injection
};

}  // namespace invfree::live
