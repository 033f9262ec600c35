// Presentation mode (key P): the picture on the whole screen with no panel, and the three
// numbers a lecture points at - t, min det F and the inverted-triangle count - large enough
// for the back row, with the solver and the playback rate against real time under them.
// Leaving it (P again, Esc) brings back the window's size and the panel as they were.
#pragma once

#include <optional>
#include <string>

#include "app/live/live_controller.h"
#include "app/live/live_panel.h"

namespace invfree::live {

// The readouts over the top left of the picture (`area`: window pixels), in the banners'
// large font grown with the window's height. Their rectangle goes into ps.rects as
// "presentation".
void draw_presentation_readouts(const LiveController& lc, PanelState& ps, const WidgetRect& area,
                                std::optional<double> real_time_rate, const std::string& caption);

// Outside presentation mode, the playback rate alone at the picture's bottom right
// ("0.2× real time"), small.
void draw_real_time_rate(double rate, const WidgetRect& area);

}  // namespace invfree::live
