// The state a scene starts from: the square mesh's rest positions, optionally jittered
// by a deterministic pseudo-random displacement (SplitMix64, identical on every platform),
// and the initial velocity. `check_initial_state` rejects a start that the solver could
// not step from: an inverted triangle under a model that needs det F > 0, or a node on or
// through the ground or the ceiling.
#pragma once

#include <string>

#include "core/scene.h"

namespace invfree {

VecX initial_positions(const SceneDef& scene, const Mesh& mesh);
std::string check_initial_state(const SceneDef& scene);

}  // namespace invfree
