// The pcg+ldlt backend of LinearSolver (linear_solver.h): conjugate gradients on H p = b
// preconditioned by a *reused* LDL^T factorisation (ldlt_backend.h) of an earlier H.
//
// H changes little from one Newton iteration (and one step) to the next, so the factor of
// an earlier H is an excellent preconditioner and a few CG iterations (one sparse product
// and one pair of triangular solves each) replace a fresh factorisation. Where the contact
// terms moved since (a diagonal entry by more than 30%), an exact block solve on those
// unknowns and their neighbours (submatrix_ldlt.h) corrects the old factor, in a symmetric
// combination that stays positive definite (pcg.cpp, prepare_correction). The factor is
// renewed when the iterations it saves no longer pay for one (a cost model in flops, not
// clock time, so runs stay bit-for-bit reproducible), and at once when PCG does not
// converge within the cost of a factorisation: the direct solve is always the fallback.
//
// Contact couplings outside the pattern (SolveRequest::couplings, SparseHessian::couplings):
// a fold's node pairs that share no triangle. H is then h plus those 2x2 blocks: the
// products add them, and since no factor holds them (the factor's pattern, and its
// analysis, stay the mesh's), their nodes are always in the corrected set C, whose block
// solve (or Jacobi fallback) includes them. So a new contact costs no rebuild of the
// pattern, no new analysis and no factorisation: PCG's few extra iterations carry it
// (docs/performance.md, "Stalls").
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
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "linalg/linear_solver.h"
#include "linalg/submatrix_ldlt.h"
#include "types.h"

namespace invfree {

class SparseLdlt;

// A preconditioner whose factor has at least this many entries is applied from L rounded
// to float (SparseLdlt::keep_float_copy). The solves PCG repeats are bound by reading L,
// and float halves that: a solve pair takes ~25% less time at n_seg 128 (1.29 M entries,
// 10 MB in double) and ~30% less at n_seg 256 (6.42 M), with the same CG iterations per
// step to within 0.2%, and gains nothing at n_seg 64 (0.26 M entries, within the caches):
// `invfree_bench --benchmark_filter=LdltSolve` times a pair from both (its L_nonzeros
// counter is the factor's size). A rounded B is still an SPD preconditioner (D stays
// positive), so PCG and its stopping rules are unchanged; the direct solvers and smaller
// factors keep double.
constexpr long kFloatPreconditionerMinEntries = 1'000'000;

class ReusedFactorPcg {
 public:
  // Every buffer for `pattern` (full symmetric storage), and the cost model from the
  // analysis of `factor`, which is set to keep a float copy when it is large (above).
  void setup(const Eigen::SparseMatrix<double>& pattern, SparseLdlt& factor);

  // PCG with the factor stored earlier, while it is still worth using. False: it was not
  // (no factor, or due for renewal) or PCG did not converge within the cost of a
  // factorisation; the caller then factorises H (factorized) and solves with the new one.
  bool solve_with_stored_factor(const Eigen::SparseMatrix<double>& h, const VecX& b, VecX& x,
                                const SolveRequest& request, SparseLdlt& factor,
                                LinearSolveStats& stats);
  // After a factorisation of `h` into the factor the solves use (ok: it succeeded).
  void factorized(const Eigen::SparseMatrix<double>& h, bool ok);
  bool solve_with_new_factor(const Eigen::SparseMatrix<double>& h, const VecX& b, VecX& x,
                             const SolveRequest& request, SparseLdlt& factor,
                             LinearSolveStats& stats);
  // Forgets the stored factorisation: the next solve factorises afresh.
  void invalidate() { have_factor_ = false; }

 private:
  int run(const Eigen::SparseMatrix<double>& h, const VecX& b, VecX& x, const SolveRequest& request,
          SparseLdlt& factor, LinearSolveStats& stats);
  void prepare_correction(const Eigen::SparseMatrix<double>& h);
  void jacobi_fallback(const Eigen::SparseMatrix<double>& h);
  void apply_preconditioner(const Eigen::SparseMatrix<double>& h, const VecX& in, VecX& out,
                            SparseLdlt& factor);
  void smooth(const VecX& r);

  bool have_factor_ = false;
  bool refresh_ = false;      // renew the factor before the next solve
  double factor_cost_ = 0.0;  // flops of one numeric factorisation
  double iter_cost_ = 0.0;    // flops of one PCG iteration (a solve, a product, vector work)
  int max_iterations_ = 0;    // no more iterations than a fresh factorisation costs
  VecX r_, z_, p_, hp_, t_;
  // Diagonal correction of the reused factor (see prepare_correction).
  std::vector<int> diag_pos_;                       // position of H(i, i) in the value array
  VecX factored_diag_;                              // diag(H) when the factor was computed
  std::vector<std::vector<int>> changed_in_block_;  // the scan's finds, per vector block
  std::vector<int> changed_;      // unknowns whose diagonal moved by more than 30% since
  std::vector<char> is_changed_;  // 1 on `changed_`, 2 on the rest of `block_set_`
  std::vector<int> block_set_;    // D: `changed_` and its neighbours
  SubmatrixLdlt block_;           // H_DD = L D L^T, when use_block_
  bool use_block_ = false;
  VecX block_x_;   // S r on `block_set_` (or on `changed_`, the fallback)
  VecX smoother_;  // omega_i / H(i, i) on `changed_` (the fallback)
  // H's couplings outside the pattern (SolveRequest::couplings) in the current solve; their
  // nodes are always in C, so the block (or the fallback) carries them.
  std::span<const NodeCoupling> couplings_;
  VecX scattered_;  // S r spread over all unknowns (zero outside the set), for the couplings'
                    // product
};

}  // namespace invfree
