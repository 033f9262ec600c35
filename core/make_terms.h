// The one place that builds the incremental potential's terms from a simulation's scene
// and state (potential/incremental_potential.h lists them): which terms are on, and each
// one's data frozen for the step (x^n, x^n + h v^n, the lagged friction, the ceiling's
// target and penalty stiffness, the grab, self-contact's candidates at x^n). The step, the
// energy report and the stability verdict all use it.
#pragma once

#include "potential/incremental_potential.h"
#include "simulation.h"

namespace invfree {

// Fills `p` (its buffers are reused: a step allocates nothing) and, with self-contact,
// the candidates and lagged friction in `caches`. `boundary`: the bodies' boundary;
// nullptr leaves self-contact off (explicit integration has no self-contact force).
void make_terms(const Simulation& sim, const Boundary* boundary, StepProblem& p,
                StepCaches& caches);

// The ceiling's prescribed height one step after `nominal` (it stops at ceiling.stop).
double next_ceiling_nominal(const SceneDef& s, double nominal);
// The planes' barriers of a simulation's scene.
GroundBarrier ground_barrier_of(const Simulation& sim);
CeilingBarrier ceiling_barrier_of(const Simulation& sim);
// The bodies' boundary: the workspace's once a step has found it, else found into scratch.
const Boundary& boundary_now(const Simulation& sim, Boundary& scratch);

}  // namespace invfree
