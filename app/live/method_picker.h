// The live panel's rows for what the lecture switches: the method picker (method_choice.h:
// switching restarts the scene at t = 0 with the method, the other edited settings kept;
// its tooltip names the solver, as the det F panel and presentation mode do), and the bodies' own
// materials where a scene gives them (the mu and lambda sliders then show the scene's [material],
// which no body uses).
#pragma once

#include "app/live/live_controller.h"
#include "app/live/live_panel.h"

namespace invfree::live {

void method_row(LiveController& lc, PanelState& ps);

// "each body's own material" and a line per body, when any body has its own; nothing
// otherwise. Returns whether it drew them.
// Their rectangle goes into ps.rects as "body_materials".
bool body_materials_rows(const LiveController& lc, PanelState& ps);

}  // namespace invfree::live
