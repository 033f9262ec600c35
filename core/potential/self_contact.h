// The self-contact term of the incremental potential, as StepProblem holds it: the IPC
// point-edge barrier (self_contact_barrier.h) and lagged point-edge friction
// (self_friction.h), summed over the current candidate pairs.
//
// The candidate list is built by the broad phase (collision/broad_phase.h) in the line
// search's filter (solver/self_contact_filter.h) for the whole segment z -> z + alpha_max p
// it is asked about, with boxes around each node's and edge's path inflated by dhat; it
// then serves the CCD, every energy evaluation of the line search and the gradient and
// Hessian at the accepted point (inside those boxes). So the broad phase runs once per
// Newton iteration, plus once at the start of a step for the starting point.
// Pairs farther apart than dhat cost one distance evaluation.
// Inputs: the boundary and rest positions of every body (the per-pair dhat rule), the
// scene's dhat, kappa, the lagged friction pairs, the candidates.
// Outputs: value, gradient and the 6x6 Hessian blocks (mesh node triples).
#pragma once

#include <chrono>
#include <vector>

#include "potential/self_contact_barrier.h"
#include "potential/self_friction.h"

namespace invfree {

// What the term keeps between calls of one step (owned by the workspace).
struct SelfContactCache {
  std::vector<PointEdgePair> pairs;        // the current candidates
  std::vector<SelfFrictionPair> friction;  // lagged at x^n
  std::vector<PointEdgeHessian> hessians;  // of the last gradient/Hessian evaluation
  double ms = 0.0;  // steady-clock time spent in the term, its broad phase and CCD (a step)
};

// Adds the steady-clock time of its scope to `ms` (SelfContactCache::ms).
struct SelfContactTimer {
  double& ms;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  ~SelfContactTimer() {
    ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
};

struct SelfContact {
  bool on = false;
  const Boundary* boundary = nullptr;
  const std::vector<Vec2>* rest = nullptr;
  SelfContactParams params;
  bool ccd = true;      // the line search's CCD filter (solver/self_contact_filter.h)
  double eps_u = 1e-5;  // friction's eps_v h
  SelfContactCache* cache = nullptr;
};

// Barrier + friction over the current candidates, not scaled (+infinity on contact).
double self_contact_value(const SelfContact& c, const VecX& z, const VecX& x_start);
// gradient += scale * dE/dz; the Hessian blocks (scaled) into c.cache->hessians.
void self_contact_derivatives(const SelfContact& c, const VecX& z, const VecX& x_start,
                              double scale, VecX& gradient);

}  // namespace invfree
