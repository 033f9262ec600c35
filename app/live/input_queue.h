// The window's input in the order it happened, cut into the ImGui frames it needs so that
// no press is lost at a low frame rate. Dear ImGui 1.86 reads keys, buttons and the pointer
// as states once per frame: a key pressed and released between two frames of a fine mesh
// was never seen, and a button pressed on a node with the pointer already moved away by the
// next frame was seen where the pointer ended (a pan, not a grab). GLFW's callbacks push
// every event here; take() cuts them into frames in which no key or button changes twice
// and the pointer moves only before a button changes (a move after a change begins the
// next frame), so each press happens where and when it did. Characters and the wheel stay
// in their places between them.
#pragma once

#include <vector>

namespace invfree::live {

struct InputEvent {
  enum Kind { Key, Char, Button, Move, Leave, Scroll };
  Kind kind = Key;
  int code = 0;        // Key: GLFW key; Button: 0 left, 1 right, 2 middle; Char: code point
  bool down = false;   // Key, Button: pressed (a key's repeat is not an event here)
  float x = 0, y = 0;  // Move: window pixels; Scroll: the wheel's x and y
};

// One ImGui frame's share of the events.
struct InputFrame {
  std::vector<InputEvent> events;
};

class InputQueue {
 public:
  void push(const InputEvent& e) { events_.push_back(e); }
  // The events since the last call in frames (see above); at most `max_frames`, the rest
  // going into the last one. An empty queue gives one empty frame.
  std::vector<InputFrame> take(int max_frames = 64);

 private:
  std::vector<InputEvent> events_;
};

// The pointer and buttons as the events left them (ImGui's backend reads them from the
// system once per frame, which is what loses the order).
struct PointerState {
  bool known = false;  // a Move has arrived (before that the backend's reading stands)
  bool inside = true;  // false after a Leave
  float x = 0, y = 0;
  bool down[3] = {false, false, false};
};

// Writes a frame's events into ImGui's io after the backend's NewFrame, before
// ImGui::NewFrame: keys (and Ctrl/Shift/Alt/Super from them), characters, buttons, wheel,
// and the pointer as `pointer` holds it after them.
void apply_input_frame(const InputFrame& frame, PointerState& pointer);

}  // namespace invfree::live
