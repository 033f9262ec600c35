// Friction's kink in the line search: a sliding node that a step carries across zero slip
// stops at zero slip.
//
// Lagged friction on the ground (core/potential/friction.h) is mu_f lambda |u| while a node slides
// (|u| >= eps_u = eps_v h) and smooth only inside the window |u| < eps_u. The projected
// Hessian sees no friction curvature while the node slides, so where the node should
// stick, Newton's direction overshoots u = 0 by far more than eps_u, the next one comes
// back, and the line search can only halve one alpha for every node at once. This is the
// kink of an L1 term, and the remedy is OWL-QN's orthant projection (Andrew and Gao,
// "Scalable training of L1-regularized log-linear models", ICML 2007): a coordinate that
// the trial point moves across zero is set to zero instead. Here: every friction node
// whose slip changes sign along the step and ends beyond the window is put at u = 0 (its
// x = x^n; y, and every other node, as the step has them), where its friction is smooth
// and stiff, so the next direction keeps it or moves it on as the energy says.
// The trial point is then off the straight line z + alpha p, so the inversion filter's
// guarantee is checked again: a triangle left below 10% of its area at z (the filter's
// own rule) gets its stopped nodes back where the step put them, until none is. The
// ground filter is unaffected (only x moves), and the line search still accepts a trial
// only when the incremental potential does not increase. On a sloped ground (the course's
// 4_friction) no node is stopped: the slip is then along the slope, not x.
// Inputs: the step's problem (mesh, x^n, friction weights, eps_u), the current z, the
// straight trial z + alpha p in `trial`, and scratch space (sized on first use).
// Output: `trial` with the crossings stopped; returns how many nodes were stopped.
#pragma once

#include <vector>

#include "potential/incremental_potential.h"

namespace invfree {

struct FrictionCrossingScratch {
  std::vector<char> stopped;   // per node
  std::vector<int> nodes;      // the stopped nodes
  std::vector<double> step_x;  // and the x the step gave each of them
};

int stop_friction_crossings(const StepProblem& problem, const VecX& z, VecX& trial,
                            FrictionCrossingScratch& scratch);

}  // namespace invfree
