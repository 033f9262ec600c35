// The mesh a picture for a projector needs, shared by `invfree render`, `invfree live` and
// the web page: a square body of the scene's own elasticity meshed coarser than 16 x 16
// (compress's 4 x 4 shows eight flat patches of colour) is meshed at 16 for the picture, so
// det F varies across it. Not for the course's mass-spring grids and reduced bases, whose
// n_seg is part of the chapter, nor for bodies with their own n_seg or shape.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace invfree::render {

// The default of render's and live's --min-n-seg (0 keeps the scene's mesh).
constexpr int kProjectorMinSegments = 16;

// Raises scene.n_seg to min_n_seg where the rule above allows it and the finer scene is
// valid. Returns true when the mesh was changed.
bool refine_for_projector(SceneDef& scene, int min_n_seg);

// True when one of the command line's --set overrides ("key=value") sets mesh.n_seg: the
// user's own mesh, which the projector's rule leaves alone.
bool overrides_set_n_seg(const std::vector<std::string>& overrides);

}  // namespace invfree::render
