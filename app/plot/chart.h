// Charts drawn by invfree itself (no plotting tool): a CPU rasterizer with antialiased
// lines, markers, linear or logarithmic axes (decade ticks and labels on log axes), a
// legend, a title and free-text notes, and text from the DejaVu Sans font embedded at
// build time (stb_truetype). PNG output through stb_image_write.
//
// Inputs: a ChartSpec (series in data units; non-finite points and, on a log axis,
// points <= 0 are skipped). Output: an Image, RGBA8, rows top to bottom.
// Link target: invfree_plot (app/plot/CMakeLists.txt).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/colormap.h"

namespace invfree {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes, row-major, top row first
};

struct Series {
  std::string label;  // legend entry; an empty label is left out of the legend
  std::vector<double> x, y;
  Rgb color{0.0f, 0.0f, 0.0f};
  bool markers = true;
  bool lines = true;
};

struct ChartSpec {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::vector<Series> series;
  std::vector<std::string> notes;  // paragraphs printed below the legend, word-wrapped
  int width = 1280, height = 800;
};

// Draws the chart. Never fails: an empty chart (no finite points) gets default axes.
Image render_chart(const ChartSpec& spec);

// Writes `image` as a PNG, atomically (app/output_files.h). Returns "" or a one-line error.
std::string write_png(const std::string& path, const Image& image);

}  // namespace invfree
