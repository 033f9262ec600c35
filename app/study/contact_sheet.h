// The stability contact sheet: one row per method, one column per stress scene; each
// cell draws the run's final frame (or the last good frame before the failing step, or
// the frame that broke a check) with every triangle coloured by det F (app/colormap.h),
// the ground and the ceiling, and the verdict underneath; an inverted triangle (often a
// sliver right after det F crossed 0) is also ringed in the inverted colour; mesh edges
// only where triangles are large on screen (a fine mesh shows its colour, not its edges).
// A failed cell is framed and captioned red, an inversion its model allows in a neutral
// blue, an ok cell gives the smallest det F of its run with its colour (how close it came).
// A det F colour bar closes the sheet.
#pragma once

#include <memory>

#include "app/plot/canvas.h"
#include "app/study/stability.h"

namespace invfree {

Rgb cell_class_color(CellClass c);
// The verdict under a cell: "ok", "penetrated", ..., "inverted, allowed".
std::string cell_caption(const StabilityCell& cell);

std::unique_ptr<Canvas> contact_sheet(const StabilityResult& result, ChartFormat format);

// One cell's picture of a frame: world window [-0.85, 0.85] x [ground - 0.05, ground + 1.65],
// clipped to the cell.
void draw_frame(Canvas& canvas, const Frame& frame, double x0, double y0, double size);

}  // namespace invfree
