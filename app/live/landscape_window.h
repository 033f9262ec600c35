// The live window's "Energy landscape" window: the landscape panel of
// app/live/landscape_panel.h (Psi over the singular values, every triangle's (s1, s2) as a dot
// that moves with the body, the inspected triangle's ringed) in a window of its own over the
// picture, opened by the view section's checkbox (or --landscape) and closed by its x.
// Mass-spring scenes have no Psi: the window says so. Call between ImGui::NewFrame and
// ImGui::Render.
#pragma once

#include "app/live/landscape_panel.h"
#include "app/live/live_panel.h"
#include "simulation.h"

namespace invfree::live {

// Draws the window while ps.show_landscape is on (its x turns it off), placed where it first
// appears in the window's bottom right corner: over the lower part of the det F panel (its
// colour bar) rather than the picture, which the body and the inspector share.
// `selected`: the inspected triangle (-1: none). Its rectangle goes to
// ps.rects["landscape_window"].
void draw_landscape_window(const Simulation& sim, int selected, PanelState& ps,
                           LandscapePanelCache& cache);

}  // namespace invfree::live
