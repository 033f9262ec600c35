// PCG preconditioned by a reused LDL^T factorisation (pcg.h): the cost model, the
// correction of a stale factor on the unknowns whose diagonal moved, and the iteration
// with its stopping rules.
#include "linalg/pcg.h"

#include <algorithm>
#include <cmath>

#include "linalg/blocked_vector_ops.h"
#include "linalg/sparse_ldlt.h"

namespace invfree {

using SpMat = Eigen::SparseMatrix<double>;

// The cost model counts flops, not the clock (runs stay reproducible), but a flop of the
// supernodal factorisation is cheaper than one of an iteration where its fronts are wide:
// on the 2-core machine a factorisation runs at 16 G flops/s at n_seg 256 (6.4 M entries
// of L), 9 at 128 and 5 at 64, an iteration (a float solve pair, a product) at 6.5-7
// (`invfree_bench --benchmark_filter='LdltFactorize|LdltSolve'`). So from 4 M entries a
// factorisation's flops count 0.4 times: compress at n_seg 256 refreshes its factor every
// ~5 steps instead of every ~18, CG takes 12.1 iterations per step instead of 16.5 and
// Newton 2.17 instead of 2.40, and the mean step falls by ~11% (`invfree bench --sizes 256
// --steps 300`); smaller factors keep weight 1 (0.4 made n_seg 32-128 slower).
constexpr long kWideFrontMinEntries = 4'000'000;
constexpr double kWideFrontFlopWeight = 0.4;

void ReusedFactorPcg::setup(const SpMat& pattern, SparseLdlt& factor) {
  const int n = static_cast<int>(pattern.rows());
  factor_cost_ = factor.factor_flops() *
                 (factor.factor_nonzeros() >= kWideFrontMinEntries ? kWideFrontFlopWeight : 1.0);
  iter_cost_ = factor.solve_flops() + 2.0 * pattern.nonZeros() + 12.0 * n;
  max_iterations_ = std::max(2, static_cast<int>(std::ceil(factor_cost_ / iter_cost_)));
  if (factor.factor_nonzeros() >= kFloatPreconditionerMinEntries) factor.keep_float_copy(true);
  r_.resize(n);
  z_.resize(n);
  p_.resize(n);
  hp_.resize(n);
  t_.resize(n);
  diag_pos_.resize(n);
  for (int i = 0; i < n; ++i) {
    const int* begin = pattern.innerIndexPtr() + pattern.outerIndexPtr()[i];
    const int* end = pattern.innerIndexPtr() + pattern.outerIndexPtr()[i + 1];
    diag_pos_[i] = static_cast<int>(std::lower_bound(begin, end, i) - pattern.innerIndexPtr());
  }
  factored_diag_.resize(n);
  changed_.reserve(n);
  const BlockSplit blocks = vector_blocks(n);
  changed_in_block_.resize(blocks.blocks);
  for (int b = 0; b < blocks.blocks; ++b)
    changed_in_block_[b].reserve(blocks.end(b, n) - blocks.begin(b));
  is_changed_.assign(n, 0);
  block_set_.reserve(n);
  const int block_size = std::max(64, n / 8);
  block_.reserve(n, block_size, 32L * block_size);
  block_x_.resize(n);  // S r on the block, or on C for the fallback
  scattered_.setZero(n);
  smoother_.resize(n);
}

void ReusedFactorPcg::factorized(const SpMat& h, bool ok) {
  have_factor_ = ok;
  refresh_ = false;
  const double* v = h.valuePtr();
  for (std::size_t i = 0; i < diag_pos_.size(); ++i) factored_diag_[i] = v[diag_pos_[i]];
}

bool ReusedFactorPcg::solve_with_stored_factor(const SpMat& h, const VecX& b, VecX& x,
                                               const SolveRequest& request, SparseLdlt& factor,
                                               LinearSolveStats& stats) {
  if (!have_factor_ || refresh_) return false;
  const int before = stats.pcg_iterations;
  const int outcome = run(h, b, x, request, factor, stats);
  // Renew the factor for the next solve once the iterations cost half a factorisation.
  if (outcome == 1 && (stats.pcg_iterations - before) * iter_cost_ > 0.5 * factor_cost_)
    refresh_ = true;
  return outcome == 1;
}

bool ReusedFactorPcg::solve_with_new_factor(const SpMat& h, const VecX& b, VecX& x,
                                            const SolveRequest& request, SparseLdlt& factor,
                                            LinearSolveStats& stats) {
  return run(h, b, x, request, factor, stats) == 1;
}

// The reused factor B = A_old^-1 goes stale mostly through a few diagonal entries: the
// contact barriers' and friction's stiffness on the nodes near a plane change by large
// factors from one iteration to the next (friction's whenever a node starts or stops
// sliding), the elasticity only slowly. Those unknowns C (diagonal moved by more than
// kChangedDiagonal) and their neighbours in H's graph, the set D, get an exact block
// solve S = H_DD^-1 (submatrix_ldlt.h) around B, the symmetric multiplicative (Schwarz)
// combination
//   z = S r;  z += B (r - H z);  z += S (r - H z)
// i.e. M^-1 = (I - S H) B (I - H S) + S (2 S^-1 - H) S, symmetric positive definite
// because 2 S^-1 - H_DD = H_DD is. D holds C's neighbours because where B treated a node
// as held by friction that now slides (or the reverse), the block must carry the change
// to the neighbours the node pulls on, which a diagonal smoother on C alone cannot.
// `compress`, CG iterations per step at n_seg 32 / 64 / 128 / 256: 5.05 / 7.46 / 10.10 /
// 19.19 (`build/release/app/invfree bench --sizes 32,64,128,256`).
// A set D larger than the block's buffers (n / 8 unknowns, 32 envelope entries per
// unknown) means the factor is too stale to be worth correcting: that solve falls back to
// a Jacobi smoother on C and the next one refactorises (jacobi_fallback).
// The threshold separates the contact rows, whose diagonal jumps by large factors, from
// the elasticity's, which drift by tens of percent within a few steps of compression and
// which the factor absorbs: a lower one would put a large part of the mesh into C.
constexpr double kChangedDiagonal = 0.3;

void ReusedFactorPcg::prepare_correction(const SpMat& h) {
  const int n = static_cast<int>(diag_pos_.size());
  const double* v = h.valuePtr();
  const int* outer = h.outerIndexPtr();
  const int* inner = h.innerIndexPtr();
  for (int i : block_set_) is_changed_[i] = 0;
  block_set_.clear();
  changed_.clear();
  use_block_ = false;
  // The scan over fixed blocks (the same list, in the same order, for any thread count):
  // every diagonal entry is a cache miss of its own, 1 ms on one thread at n_seg 256.
  const BlockSplit blocks = vector_blocks(n);  // as reserved by setup
  for_each_block(n, [&](int begin, int length, int b) {
    std::vector<int>& list = changed_in_block_[b];
    list.clear();
    for (int i = begin; i < begin + length; ++i) {
      const double d = v[diag_pos_[i]];
      if (std::abs(d - factored_diag_[i]) > kChangedDiagonal * factored_diag_[i]) list.push_back(i);
    }
  });
  for (int b = 0; b < blocks.blocks; ++b)
    for (int i : changed_in_block_[b]) {
      changed_.push_back(i);
      is_changed_[i] = 1;
    }
  // The couplings outside the pattern are never in the factor: their nodes are always in C
  // (each coupling is listed in both orientations, so its row nodes are all of them).
  for (const NodeCoupling& c : couplings_)
    for (int i : {2 * c.row_node, 2 * c.row_node + 1})
      if (is_changed_[i] != 1) {
        changed_.push_back(i);
        is_changed_[i] = 1;
      }
  if (changed_.empty()) return;
  // D: C and its neighbours (is_changed_ 2), up to the block's capacity.
  block_set_ = changed_;
  const std::size_t capacity = static_cast<std::size_t>(block_.max_size());
  for (std::size_t a = 0; a < changed_.size() && block_set_.size() <= capacity; ++a) {
    const int i = changed_[a];
    for (int k = outer[i]; k < outer[i + 1]; ++k)
      if (!is_changed_[inner[k]]) {
        is_changed_[inner[k]] = 2;
        block_set_.push_back(inner[k]);
      }
  }
  use_block_ = block_set_.size() <= capacity && block_.factorize(h, couplings_, block_set_);
  if (!use_block_) jacobi_fallback(h);
}

// The factor is too stale for the block: S = W D_C^-1 on C now, a new factor next solve.
// The weights w_i = min(1, 1.9 / (1 + R_i)), R_i the Gershgorin radius of row i of
// D^-1/2 H_CC D^-1/2, make 2 S^-1 - H_CC diagonally dominant, so again positive definite.
void ReusedFactorPcg::jacobi_fallback(const SpMat& h) {
  const double* v = h.valuePtr();
  const int* outer = h.outerIndexPtr();
  const int* inner = h.innerIndexPtr();
  refresh_ = true;
  for (int i : changed_) {
    const double di = v[diag_pos_[i]];
    double radius = 0.0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const int j = inner[k];
      if (j != i && is_changed_[j] == 1) radius += std::abs(v[k]) / std::sqrt(di * v[diag_pos_[j]]);
    }
    smoother_[i] = radius;
  }
  // The couplings' entries too (both ends are in C; a pair listed twice counts twice, a
  // larger radius, still a valid bound).
  for (const NodeCoupling& c : couplings_)
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const int i = 2 * c.row_node + a, j = 2 * c.col_node + b;
        smoother_[i] += std::abs(c.block(a, b)) / std::sqrt(v[diag_pos_[i]] * v[diag_pos_[j]]);
      }
  for (int i : changed_) smoother_[i] = std::min(1.0, 1.9 / (1.0 + smoother_[i])) / v[diag_pos_[i]];
}

// block_x_[a] = (S r)[set[a]]: S on the block (an exact solve on D) or, as the fallback,
// the Jacobi smoother on C.
void ReusedFactorPcg::smooth(const VecX& r) {
  if (use_block_) {
    block_.solve(r, block_x_);
    return;
  }
  for (std::size_t a = 0; a < changed_.size(); ++a)
    block_x_[a] = smoother_[changed_[a]] * r[changed_[a]];
}

// out = M^-1 in (see prepare_correction); `out` must not alias `in`.
void ReusedFactorPcg::apply_preconditioner(const SpMat& h, const VecX& in, VecX& out,
                                           SparseLdlt& factor) {
  // The float copy, when kept (setup), only ever serves PCG.
  if (changed_.empty()) {
    factor.solve_float(in, out);
    return;
  }
  const double* v = h.valuePtr();
  const int* outer = h.outerIndexPtr();
  const int* inner = h.innerIndexPtr();
  const std::vector<int>& set = use_block_ ? block_set_ : changed_;
  const int m = static_cast<int>(set.size());
  smooth(in);  // z1 = S in; t = in - H z1 (z1 is nonzero on the set only: its columns)
  blocked_copy(in, t_);
  for (int a = 0; a < m; ++a) {
    const int i = set[a];
    for (int k = outer[i]; k < outer[i + 1]; ++k) t_[inner[k]] -= v[k] * block_x_[a];
  }
  if (!couplings_.empty()) {  // both ends of a coupling are in the set
    for (int a = 0; a < m; ++a) scattered_[set[a]] = block_x_[a];
    for (const NodeCoupling& c : couplings_)
      t_.segment<2>(2 * c.row_node) -= c.block * scattered_.segment<2>(2 * c.col_node);
    for (int a = 0; a < m; ++a) scattered_[set[a]] = 0.0;
  }
  factor.solve_float(t_, out);
  for (int a = 0; a < m; ++a) out[set[a]] += block_x_[a];
  // out += S (in - H out), rows of the set only (H is symmetric: row i = column i).
  // Each row on its own: in fixed blocks of the set over the pool.
  const BlockSplit rows = split_blocks(m, 256, 64);
  thread_pool().run(rows.blocks, [&](int b) {
    for (int a = rows.begin(b); a < rows.end(b, m); ++a) {
      const int i = set[a];
      double hz = 0.0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) hz += v[k] * out[inner[k]];
      t_[i] = in[i] - hz;
    }
  });
  for (const NodeCoupling& c : couplings_)
    t_.segment<2>(2 * c.row_node) -= c.block * out.segment<2>(2 * c.col_node);
  smooth(t_);
  for (int a = 0; a < m; ++a) out[set[a]] += block_x_[a];
}

// PCG from x = 0, preconditioned by the stored factor; see pcg.h for the stopping rules.
// Returns 1 converged, 0 not within max_iterations_, -1 breakdown.
int ReusedFactorPcg::run(const SpMat& h, const VecX& b, VecX& x, const SolveRequest& req,
                         SparseLdlt& factor, LinearSolveStats& stats) {
  const Eigen::Index n = b.size();
  x.setZero(n);
  couplings_ = req.couplings;
  const double b_norm = std::sqrt(blocked_dot(b, b));
  if (b_norm == 0.0) return 1;
  blocked_copy(b, r_);
  prepare_correction(h);
  apply_preconditioner(h, r_, z_, factor);
  blocked_copy(z_, p_);
  double rz = blocked_dot(r_, z_);
  const bool decide = req.threshold > 0.0 && req.lambda_min > 0.0;
  double decrease = 0.0;
  for (int k = 1; k <= max_iterations_; ++k) {
    const double php = multiply_symmetric(h, couplings_, p_, hp_);
    if (!(php > 0.0) || !std::isfinite(php)) return -1;
    const double alpha = rz / php;
    decrease += alpha * rz;  // twice the decrease of the quadratic model so far
    // x += alpha p, r -= alpha H p, |r|_2^2 and |x|_inf in one pass.
    double r_part[256], x_part[256];
    for_each_block(n, [&](int begin, int length, int block) {
      auto xb = x.segment(begin, length);
      auto rb = r_.segment(begin, length);
      xb += alpha * p_.segment(begin, length);
      rb -= alpha * hp_.segment(begin, length);
      r_part[block] = rb.squaredNorm();
      x_part[block] = xb.lpNorm<Eigen::Infinity>();
    });
    double r_squared = 0.0, x_inf = 0.0;
    for (int block = 0, blocks = vector_blocks(n).blocks; block < blocks; ++block) {
      r_squared += r_part[block];
      x_inf = std::max(x_inf, x_part[block]);
    }
    ++stats.pcg_iterations;
    const double r_norm = std::sqrt(r_squared);
    if (r_norm <= 1e-13 * b_norm) return 1;  // as accurate as a direct solve
    if (decide && x_inf < req.threshold) {
      // Newton would stop: only when the exact solution certainly would too.
      auto certain = [&](double residual_norm) {
        return x_inf + residual_norm / req.lambda_min < req.threshold;
      };
      if (certain(r_norm)) {
        // Confirm with the true residual b - H x (CG's recurrence drifts by rounding).
        multiply_symmetric(h, couplings_, x, hp_);
        const double true_squared = sum_over_blocks(n, [&](int begin, int length) {
          return (b.segment(begin, length) - hp_.segment(begin, length)).squaredNorm();
        });
        if (certain(std::sqrt(true_squared))) return 1;
      }
    } else if (alpha * rz <= req.forcing * decrease) {
      return 1;  // Newton goes on with this direction (an inexact Newton step)
    }
    apply_preconditioner(h, r_, z_, factor);
    const double rz_next = blocked_dot(r_, z_);
    if (!(rz_next > 0.0)) return -1;
    const double beta = rz_next / rz;
    rz = rz_next;
    for_each_block(n, [&](int begin, int length, int) {
      p_.segment(begin, length) = z_.segment(begin, length) + beta * p_.segment(begin, length);
    });
  }
  return 0;
}

}  // namespace invfree
