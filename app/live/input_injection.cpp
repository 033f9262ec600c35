#include "app/live/input_injection.h"

#include <imgui.h>

namespace invfree::live {

void InputInjection::apply(const Injection& inject) {
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(inject.x, inject.y);
  for (int b = 0; b < 3; ++b) io.MouseDown[b] = inject.down[b];
  io.MouseWheel += inject.wheel;
  for (int k : held_keys_) io.KeysDown[k] = false;
  held_keys_.clear();
  for (int k : inject.keys) {
    if (k < 0 || k >= static_cast<int>(IM_ARRAYSIZE(io.KeysDown))) continue;
    io.KeysDown[k] = true;
    held_keys_.push_back(k);
  }
  io.KeyCtrl = inject.ctrl;
  for (char c : inject.text) io.AddInputCharacter(static_cast<unsigned char>(c));
}

}  // namespace invfree::live
