// The live window's keyboard and mouse bindings: one table that the key handler, the F1
// help overlay and `invfree live --help` all read, so they cannot disagree.
// Key codes and modifier bits are GLFW's (header only; nothing here links GLFW). GLFW's key
// codes name a key's place on a US keyboard, so + and - are bound to the characters typed
// (the = key, numpad +, a German keyboard's + key all type one), not to a key.
#pragma once

#include <optional>
#include <span>
#include <string>

namespace invfree::live {

enum class Action {
  TogglePlay,
  Step,
  Reset,
  TogglePanel,
  ToggleHelp,
  Screenshot,
  ToggleRecord,
  FitView,
  UiScaleUp,
  UiScaleDown,
  CycleDetFPanel,
  CycleColorRange,
  Presentation,
  Back,  // Esc: closes what is open (a picker, the help, presentation mode, the inspector)
  Quit   // Ctrl+Q: Esc no longer quits, so a stray Esc cannot lose the edited settings
};

struct KeyBinding {
  int key;   // GLFW_KEY_*; kTypedKey: bound to `chars` instead
  int mods;  // GLFW_MOD_* that must be held (Shift/Alt/Super are ignored otherwise)
  Action action;
  const char* key_name;
  const char* description;
  const char* chars = nullptr;  // with key == kTypedKey: any of these characters typed
};
constexpr int kTypedKey = -1;

std::span<const KeyBinding> key_bindings();

struct MouseBinding {
  const char* gesture;
  const char* description;
};
std::span<const MouseBinding> mouse_bindings();

// The action bound to a key press with these modifiers, if any. Ctrl must match exactly
// (Ctrl+P is a screenshot, plain P is nothing).
std::optional<Action> action_for_key(int key, int mods);
// The action bound to a typed character (+, =, -), if any.
std::optional<Action> action_for_char(unsigned c);

// "Keys:\n  Space   play / pause\n ..." then the mouse gestures; for --help and the overlay.
std::string help_text();

}  // namespace invfree::live
