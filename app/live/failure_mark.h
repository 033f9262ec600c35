// A failed step marked in the picture itself, not only in the banner: a red frame around
// the picture and a stamp at its foot, so that a screenshot of a failed run cannot pass for
// a normal one (the banner may be cropped away, or covered by a window).
#pragma once

#include "app/live/live_app.h"
#include "app/live/live_controller.h"

namespace invfree::live {

// Over the picture's `area` (window pixels) while lc.banner holds a failure.
void draw_failure_mark(const LiveController& lc, const WidgetRect& area);

}  // namespace invfree::live
