#include "app/live/key_bindings.h"

#include <GLFW/glfw3.h>

#include <cstdio>

namespace invfree::live {

namespace {

constexpr KeyBinding kKeys[] = {
    {GLFW_KEY_SPACE, 0, Action::TogglePlay, "Space", "play / pause"},
    {GLFW_KEY_S, 0, Action::Step, "S", "single step (pauses)"},
    {GLFW_KEY_R, 0, Action::Reset, "R", "reset to the initial state (keeps the settings)"},
    {GLFW_KEY_TAB, 0, Action::TogglePanel, "Tab", "hide / show the panel"},
    {GLFW_KEY_F1, 0, Action::ToggleHelp, "F1", "help overlay: these keys"},
    {GLFW_KEY_P, GLFW_MOD_CONTROL, Action::Screenshot, "Ctrl+P",
     "screenshot (numbered PNG, path printed)"},
    {GLFW_KEY_R, GLFW_MOD_CONTROL, Action::ToggleRecord, "Ctrl+R",
     "start / stop recording a PNG sequence"},
    {GLFW_KEY_F, 0, Action::FitView, "F", "frame the bodies (follow them again after a pan or zoom)"},
    {kTypedKey, 0, Action::UiScaleUp, "+", "larger text and panels (UI scale; also = and numpad +)",
     "+="},
    {kTypedKey, 0, Action::UiScaleDown, "-", "smaller text and panels", "-"},
    {GLFW_KEY_D, 0, Action::CycleDetFPanel, "D", "det F panel: beside / over the picture / hidden"},
    {GLFW_KEY_C, 0, Action::CycleColorRange, "C",
     "det F colours: fixed 0.25 to 4 / auto over the run / auto per frame"},
    {GLFW_KEY_P, 0, Action::Presentation, "P",
     "presentation: full screen, no panel, large t, min det F, inverted count"},
    {GLFW_KEY_ESCAPE, 0, Action::Back, "Esc",
     "close the open picker, help, presentation or inspector (never quits)"},
    {GLFW_KEY_Q, GLFW_MOD_CONTROL, Action::Quit, "Ctrl+Q", "quit"},
};

constexpr MouseBinding kMouse[] = {
    {"click a triangle", "inspect it (outlined; the Inspector; empty space releases it)"},
    {"left-drag a node", "pull it (a spring toward the cursor, only while dragging)"},
    {"left/right-drag", "pan the view"},
    {"wheel", "zoom about the cursor"},
};

}  // namespace

std::span<const KeyBinding> key_bindings() {
  return kKeys;
}
std::span<const MouseBinding> mouse_bindings() {
  return kMouse;
}

std::optional<Action> action_for_key(int key, int mods) {
  const int ctrl = mods & GLFW_MOD_CONTROL;
  for (const auto& b : kKeys)
    if (b.key != kTypedKey && b.key == key && (b.mods & GLFW_MOD_CONTROL) == ctrl) return b.action;
  return std::nullopt;
}

std::optional<Action> action_for_char(unsigned c) {
  for (const auto& b : kKeys)
    if (b.key == kTypedKey && c > 0 && c < 128)
      for (const char* p = b.chars; *p; ++p)
        if (static_cast<unsigned>(*p) == c) return b.action;
  return std::nullopt;
}

std::string help_text() {
  std::string s = "Keys:\n";
  char line[160];
  for (const auto& b : kKeys) {
    std::snprintf(line, sizeof line, "  %-8s %s\n", b.key_name, b.description);
    s += line;
  }
  s += "Mouse:\n";
  for (const auto& m : kMouse) {
    std::snprintf(line, sizeof line, "  %-17s %s\n", m.gesture, m.description);
    s += line;
  }
  return s;
}

}  // namespace invfree::live
