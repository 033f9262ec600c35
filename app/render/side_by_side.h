// Two views of one scene in one frame, left and right (`invfree render --compare`): each
// view is a whole frame of half the width, drawn by the renderer on its own; what makes
// them comparable is chosen once for both: here the det F colour range from both states'
// det F and a camera that frames the bodies of both (so equal positions are equal pixels
// in either half); Psi's and stress's scale from both states' values in
// ColorRangeTracker::apply_field (view_choices.h), so equal colours are equal values.
// Inputs: the two states of a frame (or their pixels). Outputs: DrawOptions fields, a
// camera, the joined pixels.
#pragma once

#include <cstdint>
#include <vector>

#include "app/render/camera.h"
#include "app/render/renderer.h"

namespace invfree::render {

// A state holding every node of `states` (the first one's scene and time): what a
// FollowCamera follows so that it frames the bodies of all of them.
FrameState nodes_of_all(const std::vector<const FrameState*>& states);

// The det F range the automatic colour scale is chosen from for states shown together:
// the lowest of their bulk_det_f_range lows and the highest of their highs (one state's
// own range; {1, 1} when none has triangles).
std::pair<double, double> joint_bulk_det_f_range(const std::vector<const FrameState*>& states);

// `left` and `right` (RGBA8, half_width x height, bottom row first, as read_pixels gives
// them) side by side into `out` (2 half_width x height, the same order).
void join_side_by_side(const std::vector<std::uint8_t>& left,
                       const std::vector<std::uint8_t>& right, int half_width, int height,
                       std::vector<std::uint8_t>* out);

}  // namespace invfree::render
