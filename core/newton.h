// Projected Newton minimisation of one step's incremental potential (lecture 9's demo):
//   repeat: p = -H^-1 g (H projected to PSD);  stop when |p|_inf / h < tol
//           alpha = min(1, inversion-free filter, plane filter)
//           halve alpha until E(z + alpha p) <= E(z);  z += alpha p
// The ceiling (the demo's moving Dirichlet boundary) is an unknown pulled to its target
// by a penalty; as soon as jumping to the target keeps every node at least 10% of its
// gap away, it is set exactly there and eliminated. If Newton converges before that, the
// penalty stiffness doubles (as in the demo).
// Inputs: the step's problem, z = [x; c] at the start (feasible). Output: z at the
// minimum (or the last iterate on failure) and a report; never loops forever.
#pragma once

#include "core/incremental_potential.h"
#include "core/linear_solver.h"
#include "core/step_status.h"

namespace invfree {

struct NewtonSettings {
  double tol = 1e-2;           // on |p|_inf / h, in m/s
  int max_iterations = 100;
  bool inversion_filter = true;
  int max_halvings = 60;       // 2^-60: below double precision of any step
};

struct NewtonResult {
  StepStatus status = StepStatus::Ok;
  int iterations = 0;
  double residual = 0.0;  // |p|_inf / h of the last direction
  double energy = 0.0;    // incremental potential at the returned z
};

struct NewtonWorkspace {
  SparseHessian hessian;
  LinearSolver solver;
  VecX gradient, direction, trial;
};

NewtonResult minimize_incremental_potential(StepProblem& problem, const NewtonSettings& settings,
                                            NewtonWorkspace& ws, VecX& z);

}  // namespace invfree
