// The stability contact sheet: one row per method, one column per stress scene; each
// cell draws the run's final frame (or the last good frame before the failing step, or
// the frame that broke a check) with every triangle coloured by det F (app/colormap.h),
// the ground and the ceiling, and the verdict underneath; an inverted triangle (often a
// sliver right after det F crossed 0) is also ringed in the inverted colour. A det F
// colour bar closes the sheet.
#pragma once

#include "app/plot/chart.h"
#include "app/study/stability.h"

namespace invfree {

Image contact_sheet(const StabilityResult& result);

// One cell's picture of a frame: world window [-0.85, 0.85] x [ground - 0.05, ground + 1.65].
void draw_frame(Image& image, const Frame& frame, int x0, int y0, int size);

}  // namespace invfree
