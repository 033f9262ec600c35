#include "app/live/panel_layout.h"

#include <algorithm>

namespace invfree::live {

PanelPlacement place_panel(float window_w, float window_h, float ui_scale, bool open) {
  PanelPlacement p;
  const float want = kPanelDesignWidth * ui_scale;
  // Docked, a panel over three quarters of the window would leave no picture beside it (a
  // phone's 390 px at UI scale 1). Below that it stays docked, as the desktop has it (at UI
  // scale 3 on 1920 px, 61%): a drawer there would hide the body behind it.
  p.drawer = want > 0.75f * window_w;
  p.w = std::min(want, window_w);
  p.h = window_h;
  p.reserved = open && !p.drawer ? p.w : 0.0f;
  return p;
}

bool panel_starts_open(float window_w, float window_h, float ui_scale, float det_f_panel_w) {
  const PanelPlacement p = place_panel(window_w, window_h, ui_scale, true);
  if (p.drawer) return false;
  return window_w - p.w - det_f_panel_w >= 0.4f * window_w;
}

}  // namespace invfree::live
