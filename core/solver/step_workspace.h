// The solver's private workspace of a Simulation: the step's problem (every term's data,
// frozen for the step), the terms' caches, Newton's buffers (sparse pattern, symbolic
// factorisation, the reused factor) and scratch vectors. Built once per mesh; a step
// allocates nothing.
// Embedding programs never need it (invfree.h does not include it); tests and benchmarks
// that look inside a step do.
#pragma once

#include <vector>

#include "potential/incremental_potential.h"
#include "scene/boundary.h"
#include "solver/newton.h"

namespace invfree {

struct StepWorkspace {
  StepProblem problem;
  StepCaches caches;  // what the terms keep between calls of a step
  NewtonWorkspace newton;
  VecX z, x_new, v_new;
  std::vector<Spring> springs;    // a mass-spring scene's (problem.springs points here)
  std::vector<int> spring_slots;  // 16 per spring
  std::vector<double> spring_count;  // per node, the springs ending there ([gravity] per_spring)
  Boundary boundary;              // the bodies' boundary (self-contact; built on first use)
  std::vector<std::array<int, 2>> edge_pairs;  // scratch of the intersection check
};

}  // namespace invfree
