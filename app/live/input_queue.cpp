#include "app/live/input_queue.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cfloat>
#include <set>

namespace invfree::live {

std::vector<InputFrame> InputQueue::take(int max_frames) {
  std::vector<InputFrame> frames(1);
  std::set<int> keys, buttons;  // changed in the frame being filled
  bool button_changed = false;
  auto next_frame = [&] {
    if (static_cast<int>(frames.size()) >= max_frames) return;  // the rest into the last
    frames.emplace_back();
    keys.clear();
    buttons.clear();
    button_changed = false;
  };
  for (const InputEvent& e : events_) {
    switch (e.kind) {
      case InputEvent::Key:
        if (keys.count(e.code)) next_frame();
        keys.insert(e.code);
        break;
      case InputEvent::Button:
        if (buttons.count(e.code)) next_frame();
        buttons.insert(e.code);
        button_changed = true;
        break;
      case InputEvent::Move:
      case InputEvent::Leave:
        if (button_changed) next_frame();
        break;
      case InputEvent::Char:
      case InputEvent::Scroll:
        break;
    }
    frames.back().events.push_back(e);
  }
  events_.clear();
  return frames;
}

void apply_input_frame(const InputFrame& frame, PointerState& pointer) {
  ImGuiIO& io = ImGui::GetIO();
  for (const InputEvent& e : frame.events) {
    switch (e.kind) {
      case InputEvent::Key:
        if (e.code >= 0 && e.code < static_cast<int>(IM_ARRAYSIZE(io.KeysDown)))
          io.KeysDown[e.code] = e.down;
        break;
      case InputEvent::Char:
        io.AddInputCharacter(static_cast<unsigned>(e.code));
        break;
      case InputEvent::Button:
        if (e.code >= 0 && e.code < 3) pointer.down[e.code] = e.down;
        break;
      case InputEvent::Move:
        pointer.known = true;
        pointer.inside = true;
        pointer.x = e.x;
        pointer.y = e.y;
        break;
      case InputEvent::Leave:
        pointer.known = true;
        pointer.inside = false;
        break;
      case InputEvent::Scroll:
        io.MouseWheelH += e.x;
        io.MouseWheel += e.y;
        break;
    }
  }
  io.KeyCtrl = io.KeysDown[GLFW_KEY_LEFT_CONTROL] || io.KeysDown[GLFW_KEY_RIGHT_CONTROL];
  io.KeyShift = io.KeysDown[GLFW_KEY_LEFT_SHIFT] || io.KeysDown[GLFW_KEY_RIGHT_SHIFT];
  io.KeyAlt = io.KeysDown[GLFW_KEY_LEFT_ALT] || io.KeysDown[GLFW_KEY_RIGHT_ALT];
  io.KeySuper = io.KeysDown[GLFW_KEY_LEFT_SUPER] || io.KeysDown[GLFW_KEY_RIGHT_SUPER];
  for (int b = 0; b < 3; ++b) io.MouseDown[b] = pointer.down[b];
  if (pointer.known)
    io.MousePos = pointer.inside ? ImVec2(pointer.x, pointer.y) : ImVec2(-FLT_MAX, -FLT_MAX);
}

}  // namespace invfree::live
