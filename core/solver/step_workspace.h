// The solver's private workspace of a Simulation: the step's problem (every term's data,
// frozen for the step), Newton's buffers (sparse pattern, symbolic factorisation, the
// reused factor) and scratch vectors. Built once per mesh; a step allocates nothing.
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
  NewtonWorkspace newton;
  VecX z, x_new, v_new;
  std::vector<Spring> springs;    // a mass-spring scene's (problem.springs points here)
  std::vector<int> spring_slots;  // 16 per spring
  // Self-contact: the bodies' boundary (built on first use) and the term's candidates.
  Boundary boundary;
  SelfContactCache contact;
  std::vector<std::array<int, 2>> edge_pairs;  // scratch of the intersection check
};

struct Simulation;
// The planes' barriers of a simulation's scene, as the step and the energy report use them.
GroundBarrier ground_barrier_of(const Simulation& sim);
CeilingBarrier ceiling_barrier_of(const Simulation& sim);
// The bodies' boundary: the workspace's once a step has found it, else found into scratch.
const Boundary& boundary_now(const Simulation& sim, Boundary& scratch);

}  // namespace invfree
