// Charts drawn by invfree with Cairo (app/plot/canvas.h): lines, markers with optional
// point labels (one that would overlap another is left out), linear or logarithmic axes (decade
// ticks and labels on log axes), a legend, a title, and notes (word-wrapped below the plot; the
// chart grows to hold them, so nothing is cut off). Panels stack vertically into one drawing,
// written as PNG, SVG or PDF.
//
// Inputs: ChartSpecs (series in data units; non-finite points and, on a log axis, points
// <= 0 are skipped). Output: a Canvas (its texts() say what was written where).
// Link target: invfree_plot (app/plot/CMakeLists.txt).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/colormap.h"
#include "app/plot/canvas.h"
#include "app/plot/image.h"

namespace invfree {

struct Series {
  std::string label;  // legend entry; an empty label is left out of the legend
  std::vector<double> x, y;
  Rgb color{0.0f, 0.0f, 0.0f};
  bool markers = true;
  bool lines = true;
  double dash = 0.0;                        // > 0: a dashed line (dash length at 1280 x 800)
  std::vector<std::string> point_labels{};  // empty, or one (possibly empty) per point
};

struct ChartSpec {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::vector<Series> series;
  std::vector<std::string> notes;  // paragraphs printed below the plot, word-wrapped
  // When not empty, an axis's only ticks, each labelled with its value (counts such as
  // thread counts, where a 1-2-5 step would put ticks at 1.2 threads).
  std::vector<double> x_ticks, y_ticks;
  int width = 1280, height = 800;  // the plot's part; the notes add to the height
  // Text, lines and markers grow by this factor (a slide read from the back row: 1.6 at
  // 1920 x 1080 gives 56-px titles and 35-px tick labels).
  double type_scale = 1.0;
};

// The height the chart takes, its notes included.
double chart_height(const ChartSpec& spec);

// Draws the chart with its top-left corner at the canvas's origin. Never fails: an empty
// chart (no finite points) gets default axes.
void draw_chart(Canvas& canvas, const ChartSpec& spec);

// The panels one below the other in one drawing, as wide as the widest.
std::unique_ptr<Canvas> chart_canvas(const std::vector<ChartSpec>& panels, ChartFormat format);

}  // namespace invfree
