// The self-contact term of the incremental potential: the IPC point-edge barrier
// (self_contact_barrier.h) and lagged point-edge friction (self_friction.h), summed over
// the current candidate pairs. A whole-mesh term (term.h) with a stateful filter.
//
// The candidate list is built by the broad phase (collision/broad_phase.h) in the term's
// filter (max_step) for the whole segment z -> z + alpha_max p it is asked about, with
// boxes around each node's and edge's path inflated by dhat; the additive CCD (solver/ccd.h)
// runs over it. The list then serves every energy evaluation of the line search and the
// gradient and Hessian at the accepted point (inside those boxes). So the broad phase runs
// once per Newton iteration, plus once at the start of a step (begin) for the starting
// point. Pairs farther apart than dhat cost one distance evaluation.
// While the clearance certificate (self_contact_clearance.h, measured on accepted states)
// can answer for the motion asked about, begin and the filter take their candidates from
// it instead of the broad phase: none where nothing can be within its dhat (then the CCD is
// skipped too, and the value, derivatives and path_step of the empty list are answered
// without work and untimed), otherwise the few measured pairs that may be.
// The candidates, the lagged friction pairs, the Hessian blocks and the time spent live in
// SelfContactCache (StepCaches::contact), which every call receives through TermPoint.
// Inputs: the boundary and rest positions of every body (the per-pair dhat rule), the
// scene's dhat, kappa, the lagged friction pairs, the candidates.
// Outputs: value, gradient and the 6x6 Hessian blocks (mesh node triples).
#pragma once

#include <chrono>
#include <vector>

#include "potential/self_contact_barrier.h"
#include "potential/self_contact_clearance.h"
#include "potential/self_friction.h"
#include "potential/term.h"

namespace invfree {

// What the term keeps between calls of one step (StepCaches::contact).
struct SelfContactCache {
  std::vector<PointEdgePair> pairs;        // the current candidates
  std::vector<SelfFrictionPair> friction;  // lagged at x^n
  std::vector<PointEdgeHessian> hessians;  // of the last gradient/Hessian evaluation
  // Kept across steps: nothing close since the last accepted state measured
  // (self_contact_clearance.h); the step's invariant check measures it again.
  SelfContactClearance clearance;
  std::vector<PointEdgePair> near;  // the invariant check's near pairs (scratch)
  PairSumScratch pair_sums;         // the sums over pairs on the threads
  // Steady-clock time spent in the term (a step): its broad phase, CCD, energy, derivatives
  // and the step's intersection check.
  double ms = 0.0;
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

// Room for what the broad phase, the candidates and the clearance's measurement usually
// need on this boundary, so that steps allocate nothing once the run has started (the grid's
// cells exactly; the lists for a few dozen pairs a node; they still grow if a fold needs more).
void reserve_self_contact(const Boundary& boundary, SelfContactCache& cache, BroadPhaseGrid& grid);

struct SelfContact {
  static constexpr EnergyKind kind = EnergyKind::Contact;
  static constexpr bool scaled_by_h2 = true;
  bool on = false;
  const Boundary* boundary = nullptr;
  const std::vector<Vec2>* rest = nullptr;
  SelfContactParams params;
  bool ccd = true;      // the filter's CCD (off: the broad phase alone)
  double eps_u = 1e-5;  // friction's eps_v h

  // Barrier + friction over the current candidates, times scale (+infinity on contact).
  double value(const TermPoint& at, double scale) const;
  // Gradient into out.gradient, Hessian blocks into the pattern (or `outgrown`).
  void add_derivatives(const TermPoint& at, double scale, Assembly& out) const;
  // Candidates over z -> z + alpha dir, then the largest collision-free step in [0, alpha].
  double max_step(const TermPoint& at, const VecX& dir, double alpha) const;
  // The largest collision-free fraction of z -> trial over the current candidates (a trial
  // the friction-crossing stop moved off the line; each node stays inside its path's box).
  double path_step(const TermPoint& at, const VecX& trial) const;
  // Candidates around the point z (no motion): Newton's start.
  void begin(const TermPoint& at) const;
  // The barrier as Contact, the friction as Friction, over the current candidates.
  void add_energy_by_kind(const TermPoint& at, EnergyBins& bins) const;
  // The candidates of the motion z -> z + alpha dir (dir null: the point z) from the
  // clearance certificate alone, when it can answer (true): none, or its near pairs.
  bool clear_candidates(const TermPoint& at, const VecX* dir, double alpha) const;
};

}  // namespace invfree
