// One stability run's frame as a picture (the contact sheet's cells, the sheet pages'
// thumbnails): every triangle coloured by det F (app/colormap.h), the ground and the
// ceiling; an inverted triangle (often a sliver right after det F crossed 0) is drawn last
// and ringed in the inverted colour; mesh edges only where triangles are large on screen
// (a fine mesh shows its colour, not its edges). Everything is clipped to the picture.
#pragma once

#include "app/plot/canvas.h"
#include "app/study/run.h"

namespace invfree {

// The full sheet's cell: a square, world window 1.7 side lengths wide from just below the
// ground up (the same scale in every cell of a row), widened to frame several bodies.
void draw_frame(Canvas& canvas, const Frame& frame, double x0, double y0, double size);

// A sheet page's thumbnail, w x h: framed on the bodies (every node), the ground and a
// ceiling close above them, with a margin, so a body squashed to a strip or thrown apart
// fills the picture.
void draw_frame_fitted(Canvas& canvas, const Frame& frame, double x0, double y0, double w,
                       double h);

}  // namespace invfree
