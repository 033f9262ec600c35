// The full stability contact sheet (`invfree stability --full-sheet`: stability.png):
// one row per method, one column per stress scene; each cell draws the run's final frame
// (or the last good frame before the failing step, or the frame that broke a check;
// frame_thumbnail.h) and the verdict underneath. Too large for a projector (11 x 15
// cells); a class sees the sheet's pages (stability_sheet_pages.h).
// A failed cell is framed and captioned red, an inversion its model allows in a neutral
// blue, an ok cell gives the smallest det F of its run with its colour (how close it came).
// A det F colour bar closes the sheet.
#pragma once

#include <memory>

#include "app/plot/canvas.h"
#include "app/study/frame_thumbnail.h"
#include "app/study/stability.h"
#include "app/study/stability_palette.h"

namespace invfree {

Rgb cell_class_color(CellClass c);
// The verdict under a cell: "ok", "penetrated", ..., "inverted, allowed".
std::string cell_caption(const StabilityCell& cell);

std::unique_ptr<Canvas> contact_sheet(const StabilityResult& result, ChartFormat format);

// The key under a sheet, `k` times the full sheet's size, its bar starting at (x, y) (the
// "det F" label left of it): the det F colour bar with its ticks, the det F <= 0 swatch, and
// (`frames`) what a red and a blue frame mean. 520 k wide plus the swatch's text; 64 k tall
// with the frames' line, 40 k without.
void draw_sheet_key(Canvas& canvas, double x, double y, double k, bool frames);

}  // namespace invfree
