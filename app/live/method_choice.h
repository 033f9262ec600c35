// The lecture's switches as one choice in the live panel: the lecture's method, no
// projection, no inversion filter, symplectic Euler, linear elasticity - the study's
// methods of app/study/methods.h, each a set of scene overrides applied to the scene as
// edited (its material, mesh, contact and time settings kept). Which one a scene runs is
// read back from its settings, and the caption names its integrator and solver on screen.
#pragma once

#include <span>
#include <string>

#include "app/study/methods.h"

namespace invfree::live {

struct LiveMethod {
  const char* name;   // study_methods()'s
  const char* label;  // the picker's
};
// The picker's methods, in its order.
std::span<const LiveMethod> live_methods();

// The first picker method whose settings `s` has (h aside), or null (e.g. ARAP chosen with
// the model picker).
const Method* current_method(const SceneDef& s);

// `current` switched to `to`: the method's overrides, and h over its substeps (symplectic
// Euler takes 20 steps where the implicit methods take one; switching back gives h again).
// Returns "" or why not.
std::string switch_method(const SceneDef& current, const Method& to, SceneDef* out);

// "implicit Euler, Newton with diagonal-space projection, inversion filter" and the like.
std::string solver_caption(const SceneDef& s);

}  // namespace invfree::live
