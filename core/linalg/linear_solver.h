// The Newton system H p = b (b = -g) on the fixed sparsity pattern of a SparseHessian.
//
// Backends (chosen once per pattern, see linear_solver_kind.h), one file each:
//  - ldlt (ldlt_backend.h): the project's LDL^T (sparse_ldlt.h), AMD or METIS ordering,
//    refactorised for every solve;
//  - cholmod (cholmod_backend.h): CHOLMOD's supernodal LL^T (METIS, BLAS), refactorised
//    for every solve;
//  - pcg+ldlt (pcg.h): PCG preconditioned by a reused LDL^T factorisation, which stops
//    when Newton's stopping test would decide as with the exact solution (pcg.h gives the
//    rules and the bound); the direct solve is always its fallback.
// The symbolic analysis is done once per pattern; a factorisation is numeric only. PCG
// also takes couplings outside the pattern (SolveRequest::couplings), so contacts never
// change its pattern.
//
// No allocation after `setup`: every buffer is sized there, CHOLMOD's workspace is
// recycled by a size-keyed pool (cholmod_backend.cpp), and the LDL^T's scratch is sized by
// its analysis.
#pragma once

#include <Eigen/SparseCore>
#include <memory>
#include <span>

#include "linalg/linear_solver_kind.h"
#include "linalg/node_coupling.h"
#include "types.h"

namespace invfree {

struct LinearSolveStats {
  int factorizations = 0;
  int solves = 0;          // Newton systems solved
  int pcg_iterations = 0;  // summed over those solves
  double factor_ms = 0.0;  // numeric factorisation (including a fallback's)
  double solve_ms = 0.0;   // triangular solves, PCG products and vector updates
};

struct SolveRequest {
  double threshold = 0.0;   // Newton's |p|_inf stopping threshold (tol * h); 0: none
  double lambda_min = 0.0;  // a lower bound on H's smallest eigenvalue (> 0 for PCG)
  double forcing = 1e-1;  // relative model decrease of the last CG step, for a direction that will
                          // not stop Newton (Newton's default, core/solver/newton.h); the
                          // rules that use these three: pcg.h
  // H's 2x2 blocks outside the pattern (SparseHessian::couplings): H = h + couplings. Only
  // the PCG backend takes them (solves_by_pcg); a direct backend refuses a nonempty list
  // (solve returns false).
  std::span<const NodeCoupling> couplings;
};

// True when LinearSolver::setup(pattern, kind, positive_definite) picks the PCG backend,
// the one that takes couplings outside the pattern.
bool solves_by_pcg(LinearSolverKind kind, bool positive_definite);

class LinearSolver {
 public:
  LinearSolver();
  ~LinearSolver();
  LinearSolver(LinearSolver&&) noexcept;
  LinearSolver& operator=(LinearSolver&&) noexcept;

  // Symbolic analysis for `pattern` (full symmetric storage) and every buffer. With
  // `positive_definite` false (an exact, possibly indefinite Hessian) auto means LDL^T.
  void setup(const Eigen::SparseMatrix<double>& pattern, LinearSolverKind kind,
             bool positive_definite);
  bool ready() const { return impl_ != nullptr; }
  LinearSolverKind requested() const { return requested_; }
  bool positive_definite() const { return positive_definite_; }
  // What actually runs: "ldlt", "cholmod" or "pcg+ldlt".
  const char* backend_name() const;

  // Solves H x = b. Returns false when the factorisation breaks down or x is not finite.
  bool solve(const Eigen::SparseMatrix<double>& H, const VecX& b, VecX& x,
             const SolveRequest& request, LinearSolveStats& stats);
  // Forgets the stored factorisation: the next solve factorises afresh.
  void invalidate();

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
  LinearSolverKind requested_ = LinearSolverKind::Auto;
  bool positive_definite_ = true;
};

}  // namespace invfree
