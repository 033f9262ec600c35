// The Newton system H p = b (b = -g) on the fixed sparsity pattern of a SparseHessian.
//
// Backends (chosen once per pattern, see linear_solver_kind.h):
//  - direct: the project's LDL^T (core/linalg/sparse_ldlt.h; AMD ordering, METIS nested
//    dissection from 5k unknowns) or CHOLMOD's supernodal LL^T (METIS, BLAS). The symbolic
//    analysis is done once per pattern; a factorisation is numeric only.
//  - PCG preconditioned by a *reused* factorisation: H changes little from one Newton
//    iteration (and one step) to the next, so the factor of an earlier H is an excellent
//    preconditioner and a few conjugate-gradient iterations (one sparse product and one
//    pair of triangular solves each) replace a fresh factorisation. Where the contact
//    terms moved since (a diagonal entry by more than 30%), an exact block solve on those
//    unknowns and their neighbours (core/linalg/submatrix_ldlt.h) corrects the old factor, in a
//    symmetric combination that stays positive definite. The factor is renewed
//    when the iterations it saves no longer pay for one (a cost model in flops, not clock
//    time, so runs stay bit-for-bit reproducible), and at once when PCG does not converge
//    within the cost of a factorisation: the direct solve is always the fallback.
//
// Accuracy of an inexact p, and Newton's stopping test |p|_inf < threshold: PCG runs until
// the *decision* of the test is the one the exact solution p* would give. With H = M + K,
// K positive semi-definite (projected elasticity, barriers, friction, the ceiling), every
// eigenvalue of H is at least `lambda_min` (the smallest node mass, or the ceiling's
// penalty), so the error obeys |p - p*|_inf <= |p - p*|_2 <= |b - H p|_2 / lambda_min.
// PCG stops when either
//   |p|_inf + bound < threshold   (Newton stops, and p* would stop it too), or
//   |p|_inf >= threshold and the last CG step decreased the quadratic model by less than
//                                 `forcing` times its total decrease so far (Newton goes on;
//                                 an inexact Newton step, whatever p* would have said: going
//                                 on once more never stops Newton early), or
//   the residual is at the level of a direct solve's rounding (relative 1e-13).
// The forcing test measures the error in H's energy norm (what the line search feels);
// a residual 2-norm would be dominated by the stiff contact rows and take more iterations
// for the same Newton progress.
// The bound uses the true residual b - H p (recomputed, not CG's recurrence). Every
// direction PCG returns from a zero start is a descent direction (g.p = -p.H p* < 0 for
// every CG iterate), so the line search and its invariants are unchanged.
//
// No allocation after `setup`: every buffer is sized there, CHOLMOD's workspace is
// recycled by a size-keyed pool (core/linalg/linear_solver.cpp), and the LDL^T's scratch is
// sized by its analysis.
#pragma once

#include <Eigen/SparseCore>
#include <memory>

#include "linalg/linear_solver_kind.h"
#include "types.h"

namespace invfree {

class SparseLdlt;

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
                          // not stop Newton (Newton's default, core/solver/newton.h)
};

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

// The factorisation PCG reuses is the project's own LDL^T (core/linalg/sparse_ldlt.h):
// its triangular solves, which CG repeats every iteration while a factorisation comes
// about once in ten steps, run on two threads along the elimination tree. From this many
// unknowns it uses METIS's nested-dissection ordering (through CHOLMOD's analysis: less
// fill, a balanced tree) instead of AMD, and from kParallelLdltMinUnknowns it splits the
// tree into kLdltBins parts (fixed, whatever the thread count, so results are
// bit-identical on any machine).
constexpr int kNestedDissectionMinUnknowns = 5000;
constexpr int kParallelLdltMinUnknowns = 1000;
constexpr int kLdltBins = 2;
// A PCG preconditioner whose factor has at least this many entries is applied from L
// rounded to float (SparseLdlt::keep_float_copy): in double it is larger than the 32 MB
// L3 cache (n_seg 256: 6.4M entries, 51 MB), and its solves, bound by memory traffic, are
// most of a step; float halves the traffic
// (`build/release/tests/bench/invfree_bench --benchmark_filter=LdltSolve/n_seg:256`
// times a solve pair from both).
// A rounded B is still an SPD preconditioner (D stays positive), so PCG and its stopping
// rules are unchanged; the direct solvers and smaller factors keep double.
constexpr long kFloatPreconditionerMinEntries = 4'000'000;

// The LDL^T backend's analysis of `pattern` exactly as the solver makes it (ordering and
// bins above), for benchmarks and tests that time a SparseLdlt of their own.
void analyze_like_the_solver(const Eigen::SparseMatrix<double>& pattern, SparseLdlt& ldlt);

}  // namespace invfree
