// Projected Newton minimisation of one step's incremental potential (lecture 9's demo):
//   start:  z = x^n, or (while the ceiling moves) x^n moved toward the inertial prediction
//           x^n + h v^n as far as the line-search filters allow (a feasible warm start)
//   repeat: p = -H^-1 g (H projected to PSD), or with a reduced basis B the subspace's
//           p = -B (B^T H B)^-1 B^T g;  stop when |p|_inf / h < tol
//           alpha = min(1, every term's filter)           (largest_safe_step)
//           halve alpha until E(z + alpha p) <= E(z);  z += alpha p
// The ceiling (the demo's moving Dirichlet boundary) is an unknown pulled to its target by
// a penalty (potential/ceiling_penalty.h); as soon as jumping to the target keeps every
// node at least 10% of its gap away, it is set exactly there and eliminated. If Newton
// converges before that, the penalty stiffness doubles (as in the demo).
//
// The warm start changes where Newton begins, not what it converges to or how it stops:
// without forces the minimiser is exactly x^n + h v^n, and near it whenever the motion is
// smooth. The filters keep the start feasible. The caller uses it only while the ceiling
// moves: once the boundary is at rest, starting at x^n (the reference's choice) lets a
// body whose remaining motion is within the tolerance stop, as in the demo.
//
// Two safeguards for the non-smooth and non-convex parts of E change the path Newton
// takes, never the energy, the stopping test or the invariants (each off by a setting):
//  - step expansion: when the full step is taken and E falls at least 1.5x what the
//    quadratic model predicts, the true curvature along p is below half the model's (a
//    buckling or rolling mode whose negative curvature the PSD projection clamps to zero,
//    or a sliding node whose friction is linear); alpha doubles while E keeps falling and
//    the filters allow, up to 16.
//  - friction crossing stop (solver/friction_crossing.h): a sliding node that the trial
//    point carries across zero slip stops there instead of oscillating around it.
// Their effect on `compress` (Newton iterations per step, the worst step) is measured by
// `invfree study` / `invfree stability` with the method `plain-line-search` (both off);
// see docs/study.md.
//
// Newton knows no particular term: the energy, the derivatives, the filters (each term's
// largest safe step, potential/term.h), the control terms' stopping test (the ceiling's
// penalty) and the Hessian's eigenvalue bound all come from the problem's list of terms
// (potential/incremental_potential.h). A stateful filter (self-contact's: the broad phase
// over the segment it checks, then the additive CCD) fills a candidate list that serves
// every energy until the next filter call; a trial that a friction-crossing stop moved off
// the line is checked along its own path (path_step) and, if that path is not safe,
// replaced by the straight trial; step expansion checks the longest expansion once (its
// candidates cover every shorter one).
// One rule decides a new symbolic analysis of the linear solver: prepare_linear_solver,
// called before every solve (a changed pattern or changed solver settings). Where PCG
// solves a projected Hessian the pattern never changes: contact blocks outside it are kept
// as couplings (SparseHessian::keep_couplings) that PCG carries (linalg/pcg.h); the direct
// solvers' factor needs every block, so there a new contact grows the pattern.
//
// The linear solve may be inexact (PCG, see linalg/pcg.h); it is run until the
// stopping decision is the one the exact direction would give, and each of its directions
// is a descent direction, so the test and the invariants are exactly those of a direct solve.
// Inputs: the step's problem, z = [x; c] at the start (feasible). Output: z at the
// minimum (or the last iterate on failure) and a report; never loops forever.
#pragma once

#include <Eigen/Dense>

#include "linalg/linear_solver.h"
#include "potential/incremental_potential.h"
#include "solver/friction_crossing.h"
#include "solver/step_status.h"

namespace invfree {

struct NewtonSettings {
  double tol = 1e-2;  // on |p|_inf / h, in m/s
  LinearSolverKind linear_solver = LinearSolverKind::Auto;
  // The Hessian is projected to PSD by every term (PCG may run; hessian_lower_bound holds).
  bool projected = true;
  int max_iterations = 100;
  int max_halvings = 60;   // 2^-60: below double precision of any step
  bool predictor = false;  // warm start from the filtered x^n + h v^n
  // PCG stops when a CG step adds less than this fraction to the model decrease
  // (linalg/pcg.h): looser directions, hardly more Newton iterations.
  double forcing = 1e-1;
  bool step_expansion = true;          // see above
  bool friction_crossing_stop = true;  // see above
};

struct NewtonResult {
  StepStatus status = StepStatus::Ok;
  int iterations = 0;
  double residual = 0.0;  // |p|_inf / h of the last direction
  double energy = 0.0;    // incremental potential at the returned z
  // Where the time went (ms): gradient + Hessian assembly, and line search (filters and
  // energy evaluations); the factorisation and solve times are in `linear`.
  double assembly_ms = 0.0;
  double line_search_ms = 0.0;
  int energy_evaluations = 0;
  int stopped_nodes = 0;      // friction nodes stopped at u = 0 in accepted steps
  int expanded_steps = 0;     // accepted steps longer than the Newton step
  int penalty_doublings = 0;  // times the ceiling's penalty stiffness doubled
  LinearSolveStats linear;
};

// Newton's step in a subspace (scene/reduced_basis.h): p = B (B^T H B)^-1 (-B^T g), the
// r x r system dense and factorised by LDL^T.
struct ReducedSolve {
  Eigen::MatrixXd basis;  // B, 2N x r; empty: the step is solved in full space
  // B^T (r x 2N, filled on first use): B^T H as a dense-times-sparse product walks H's
  // columns once with contiguous r-vectors, about 3x faster than H B.
  Eigen::MatrixXd transposed;
  Eigen::MatrixXd transposed_times_hessian, hessian;  // B^T H and B^T H B
  VecX rhs, step;                                // -B^T g and q
  Eigen::LDLT<Eigen::MatrixXd> factor;
  bool on() const { return basis.size() != 0; }
};

struct NewtonWorkspace {
  SparseHessian hessian;
  ReducedSolve reduced;
  LinearSolver solver;  // set up by the caller for the hessian's pattern
  VecX gradient, rhs, direction, trial, trial2;
  double min_node_mass = 0.0;  // for the PCG error bound (linalg/pcg.h)
  FrictionCrossingScratch crossings;
  int analyzed_pattern = 0;  // the Hessian's pattern version the solver's analysis is for
  int analyses = 0;          // symbolic analyses so far (prepare_linear_solver's setups)
};

// The one rule for a new symbolic analysis: the solver is set up again when it has none
// yet, when its settings change, or when the Hessian's pattern did (a term outgrew it).
void prepare_linear_solver(NewtonWorkspace& ws, LinearSolverKind kind, bool projected);

NewtonResult minimize_incremental_potential(StepProblem& problem, StepCaches& caches,
                                            const NewtonSettings& settings, NewtonWorkspace& ws,
                                            VecX& z);

}  // namespace invfree
