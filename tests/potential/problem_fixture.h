// A small step problem for finite-difference tests of the incremental potential: a 3x3
// square's mesh and masses, the given model (exact Hessian, no projection), gravity, and
// ground and ceiling barriers with the lecture's dhat and kappa. Callers switch on the
// rest (friction, the ceiling, the pull spring) and fill the positions.
#pragma once

#include <vector>

#include "potential/incremental_potential.h"

namespace invfree::test {

inline void set_common_terms(StepProblem& p, const Mesh& mesh, const std::vector<double>& mass,
                             Model model, double h, double ground_y) {
  p.mesh = &mesh;
  p.mass = &mass;
  p.elasticity.model = model;
  p.elasticity.lame = lame_from_young_poisson(1e4, 0.3);
  p.elasticity.projection = HessianProjection::None;
  p.h = h;
  p.gravity.on = true;
  p.gravity.g = Vec2(0.0, -9.81);
  p.ground.barrier = {0.01, 1e5, 1.0 / 3};
  p.ceiling.barrier = p.ground.barrier;
  p.ground.on = true;
  p.ground.y0 = ground_y;
}

}  // namespace invfree::test
