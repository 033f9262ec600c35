// The live window's inspector: one ImGui window ("Inspector") beside the picture showing
// the selected triangle's analysis (triangle_inspection.h) the way `invfree inspect`
// reports it: the model and the triangle's own mu and lambda, F, its polar SVD U, sigma,
// V, J, Psi, P, the Cauchy stress and its principal values, the four eigenvalues of
// dP/dF as bars (negative ones red, with the value the PSD projection puts in their place
// beside), how many were clamped, and the finite-difference check of P and dP/dF.
// Call between ImGui::NewFrame and ImGui::Render.
#pragma once

#include "app/live/live_panel.h"
#include "app/live/triangle_inspection.h"

namespace invfree::live {

// Draws the window for `inspected` at the top of `area` (window pixels: the det F panel's,
// or the picture's), on its left when `left` else its right (over the picture the caller
// picks the side away from the triangle, so that the window does not hide it); placed so
// when a triangle is picked (ps.place_inspector), it can then be moved and collapsed.
// `over_picture`: the body shows through a little; over the det F panel the window is
// opaque (that panel's text would). Returns false when the user closed it (its x): the
// selection is then to be released. Its rectangle goes to ps.rects["inspector"].
bool draw_inspector(const Inspected& inspected, PanelState& ps, const WidgetRect& area, bool left,
                    bool over_picture);

}  // namespace invfree::live
