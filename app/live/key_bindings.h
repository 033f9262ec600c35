// The live window's keyboard and mouse bindings: one table that the key handler, the F1
// help overlay and `invfree live --help` all read, so they cannot disagree.
// Key codes and modifier bits are GLFW's (header only; nothing here links GLFW).
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
  Quit
};

struct KeyBinding {
  int key;   // GLFW_KEY_*
  int mods;  // GLFW_MOD_* that must be held (Shift/Alt/Super are ignored otherwise)
  Action action;
  const char* key_name;
  const char* description;
};

std::span<const KeyBinding> key_bindings();

struct MouseBinding {
  const char* gesture;
  const char* description;
};
std::span<const MouseBinding> mouse_bindings();

// The action bound to a key press with these modifiers, if any. Ctrl must match exactly
// (Ctrl+P is a screenshot, plain P is nothing).
std::optional<Action> action_for_key(int key, int mods);

// "Keys:\n  Space   play / pause\n ..." then the mouse gestures; for --help and the overlay.
std::string help_text();

}  // namespace invfree::live
