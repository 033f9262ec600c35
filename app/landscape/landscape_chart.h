// The energy landscape as a chart (`invfree landscape`): for each model a heat map of
// Psi_hat(s1, s2) on one logarithmic colour scale shared by all panels, its contour lines
// (labelled where they fit, and marked on the colour bar), the line s1 s2 = 0 (neo-Hookean's
// wall, where its energy is +infinity: hatched grey beyond it; for the invertible models a
// dashed "det F = 0" they cross with finite energy), the rest point s1 = s2 = 1, and the
// triangles' (s1, s2) as dots. Several models stand side by side on the same domain.
//
// Inputs: the spec (numbers from app/landscape/landscape.h). Output: a Canvas (Cairo,
// app/plot/canvas.h) whose texts() say what was written where. Link target:
// invfree_landscape_chart (app/landscape/CMakeLists.txt).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/landscape/landscape.h"
#include "app/plot/canvas.h"

namespace invfree {

struct LandscapeChartSpec {
  std::vector<Model> models;  // one panel each, left to right
  Lame lame;
  // The triangles' (s1, s2) drawn on every panel (empty: no dots), and what they are
  // ("compress at step 120: 8,192 triangles"), shown under the title.
  std::vector<SigmaPair> points;
  std::string points_caption;
  std::vector<std::string> notes;  // extra paragraphs under the chart
  double plot_height = 500.0;      // the panels' height in points (the text keeps its size)
};

// One model: its own domain (landscape_domain); several: common_landscape_domain().
LandscapeDomain chart_domain(const LandscapeChartSpec& spec);

std::unique_ptr<Canvas> landscape_chart(const LandscapeChartSpec& spec, ChartFormat format);

}  // namespace invfree
