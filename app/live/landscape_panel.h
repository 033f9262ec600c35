// The energy landscape in the live window and on the web page (issue 26): the same picture
// as `invfree landscape` (app/landscape/landscape.h: heat map of Psi(s1, s2) on the shared log
// scale, contours, the line s1 s2 = 0 -- neo-Hookean's wall, hatched-grey "forbidden" beyond
// it -- and the rest point), with every triangle's current (s1, s2) as a dot that moves as the
// body does (a triangle stretched beyond the domain pinned, pale, to its edge), the selected
// triangle's ringed. Drawn with Dear ImGui's draw list (no texture):
// the heat map is one mesh with a colour per grid node.
//
// Use, inside any ImGui window (the live panel, a window of its own):
//
//   LandscapePanelCache landscape_cache;   // owned by the caller, kept between frames
//   ...
//   if (ImGui::CollapsingHeader("Energy landscape")) {
//     const float w = ImGui::GetContentRegionAvail().x;
//     draw_landscape_panel(sim, selected_triangle /* -1: none */, ImVec2(w, w * 1.2f),
//                          landscape_cache);
//   }
//
// It draws at the cursor within `size`, the colour bar beside the plot or under it (whichever
// leaves the larger plot), takes the height it used (an invisible button: a click on it does
// not reach the window behind), and shows a tooltip with (s1, s2) and Psi under the mouse. The grid
// and the contours are rebuilt only when the model or the Lame parameters change (the cache); per
// frame it computes each triangle's (s1, s2) and writes the vertices. Cost
// (tests/bench/landscape_bench.cpp, docs/landscape.md): well under the 2 ms.
#pragma once

#include <imgui.h>

#include <cstdint>
#include <span>
#include <vector>

#include "app/landscape/landscape.h"

namespace invfree {

struct LandscapePanelCache {
  LandscapeCache landscape;            // grid, scale, contours
  std::vector<ImU32> node_colors;      // the grid nodes' colours (rebuilt with the grid)
  std::vector<SigmaPair> sigma;        // this frame's triangles (the Simulation overload)
  std::vector<std::uint8_t> occupied;  // dot de-duplication: one dot per few pixels
  std::vector<ImVec2> scratch;         // a contour line in pixels
  int dots_drawn = 0;                  // the last frame's (tests, the benchmark)
};

// Grid nodes per unit of sigma in the panel: every 1/32 (a node every few pixels at the
// panel's size; the chart uses a finer one).
inline constexpr int kLandscapePanelPerUnit = 32;

// The landscape of `model` with `lame`, and `points` as dots; `selected` indexes `points`
// (-1: none).
void draw_landscape_panel(Model model, const Lame& lame, std::span<const SigmaPair> points,
                          int selected, ImVec2 size, LandscapePanelCache& cache);
// The simulation's model and [material] Lame parameters, and its triangles' (s1, s2);
// `selected` is a triangle index (-1: none).
void draw_landscape_panel(const Simulation& sim, int selected, ImVec2 size,
                          LandscapePanelCache& cache);

}  // namespace invfree
