// SparseLdlt's numeric factorisation by supernodes (sparse_ldlt.h), left-looking with
// dense kernels as CHOLMOD's supernodal factorisation does (Ng & Peyton 1993; Chen, Davis,
// Hager & Rajamanickam 2008), into the very pattern and layout of L that the solves read.
//
// Supernode s, the columns [f, l] (fundamental: every column's rows below are the next
// column's and that column), with the m rows R below l: its front is a dense
// (w + m) x w column-major block, rows f .. l then R. It gets A's entries (a map made at
// the analysis), then the update of each descendant supernode d whose rows meet [f, l],
// in ascending order of d: with d's rows from the first in [f, l] on (r of them, the first
// k in [f, l]), C = L_d[those rows] D_d L_d[the first k]^T, an r x k product of dense
// blocks (Eigen's kernels), subtracted through each row's place in the front (`local`).
// Then the front's w x w block is factorised as a dense LDL^T without pivoting (panels of
// kPanel columns, each updating the columns to its right with one product), the same
// pivot checks as the rows' factorisation, and the columns go to lx_ and d_; the m x w
// block below is kept densely (ls_) for the supernodes above.
//
// A supernode needs only its descendants, which lie in its own task (done before it, in
// ascending order) or in tasks of lower levels: each front's sums are formed in an order
// fixed by the analysis, so the factor is bit-identical for any thread count.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "linalg/sparse_ldlt.h"

namespace invfree {

namespace {

// Columns per panel of a front's dense LDL^T.
constexpr int kPanel = 32;
// Descendant updates of at most this many multiply-adds run as plain loops: below it the
// setup of Eigen's blocked product costs more than the product.
constexpr long kSmallUpdate = 2048;

using Strided = Eigen::OuterStride<>;
using MatMap = Eigen::Map<Eigen::MatrixXd, 0, Strided>;
using ConstMatMap = Eigen::Map<const Eigen::MatrixXd, 0, Strided>;
using ConstVecMap = Eigen::Map<const Eigen::VectorXd>;

}  // namespace

void SparseLdlt::plan_supernodes() {
  const int n = n_;
  sn_first_.clear();
  for (int j = 0; j < n; j = snode_last_[j] + 1) sn_first_.push_back(j);
  const int ns = static_cast<int>(sn_first_.size());
  sn_first_.push_back(n);
  sn_of_.assign(n, 0);
  for (int s = 0; s < ns; ++s)
    for (int j = sn_first_[s]; j < sn_first_[s + 1]; ++j) sn_of_[j] = s;
  auto width = [&](int s) { return sn_first_[s + 1] - sn_first_[s]; };
  auto below = [&](int s) { return lp_[sn_first_[s + 1]] - lp_[sn_first_[s + 1] - 1]; };
  auto rows = [&](int s) { return li_.data() + lp_[sn_first_[s + 1] - 1]; };

  ls_begin_.assign(ns + 1, 0);
  front_size_ = update_size_ = panel_size_ = 0;
  front_width_ = 0;
  for (int s = 0; s < ns; ++s) {
    const std::size_t w = width(s), m = below(s);
    ls_begin_[s + 1] = ls_begin_[s] + static_cast<int>(m * w);
    front_size_ = std::max(front_size_, (w + m) * w);
    panel_size_ = std::max(panel_size_, w * std::min<std::size_t>(w, kPanel));
    front_width_ = std::max(front_width_, static_cast<int>(w));
  }
  ls_.assign(ls_begin_[ns], 0.0);

  // The updates: d's rows below, in runs of one supernode each (a supernode's columns are
  // consecutive, d's rows ascending); d ascending, so each supernode's list is too.
  upd_begin_.assign(ns + 1, 0);
  auto for_each_update = [&](auto&& fn) {
    for (int d = 0; d < ns; ++d) {
      const int* r = rows(d);
      const int m = below(d);
      for (int i = 0; i < m;) {
        const int s = sn_of_[r[i]], p1 = i;
        while (i < m && sn_of_[r[i]] == s) ++i;
        fn(s, d, p1, i);
      }
    }
  };
  for_each_update([&](int s, int, int, int) { ++upd_begin_[s + 1]; });
  for (int s = 0; s < ns; ++s) upd_begin_[s + 1] += upd_begin_[s];
  upd_d_.resize(upd_begin_[ns]);
  upd_p1_.resize(upd_begin_[ns]);
  upd_p2_.resize(upd_begin_[ns]);
  {
    std::vector<int> fill(upd_begin_.begin(), upd_begin_.end() - 1);
    for_each_update([&](int s, int d, int p1, int p2) {
      const int u = fill[s]++;
      upd_d_[u] = d;
      upd_p1_[u] = p1;
      upd_p2_[u] = p2;
      const std::size_t k = p2 - p1, r = below(d) - p1;
      update_size_ = std::max(update_size_, r * k + k * width(d) + r);
    });
  }

  // A's upper entry (i, k), i <= k, lies in column i of L: in i's supernode's front at
  // column i - f and k's row there.
  asm_begin_.assign(ns + 1, 0);
  for (int k = 0; k < n; ++k)
    for (int p = ap_[k]; p < ap_[k + 1]; ++p) ++asm_begin_[sn_of_[ai_[p]] + 1];
  for (int s = 0; s < ns; ++s) asm_begin_[s + 1] += asm_begin_[s];
  asm_src_.resize(asm_begin_[ns]);
  asm_dst_.resize(asm_begin_[ns]);
  std::vector<int> fill(asm_begin_.begin(), asm_begin_.end() - 1);
  for (int k = 0; k < n; ++k)
    for (int p = ap_[k]; p < ap_[k + 1]; ++p) {
      const int i = ai_[p], s = sn_of_[i];
      const int f = sn_first_[s], l = sn_first_[s + 1] - 1, w = l - f + 1, m = below(s);
      const int row = k <= l ? k - f : w + static_cast<int>(std::lower_bound(rows(s), rows(s) + m, k) - rows(s));
      const int q = fill[s]++;
      asm_src_[q] = p;
      asm_dst_[q] = (i - f) * (w + m) + row;
    }
}

void SparseLdlt::factor_supernode(int s, Scratch& scratch, bool positive_definite, bool& ok) {
  const int f = sn_first_[s], l = sn_first_[s + 1] - 1, w = l - f + 1;
  const int m = lp_[l + 1] - lp_[l], ld = w + m;
  const int* rows = li_.data() + lp_[l];
  double* front = scratch.front.data();
  int* local = scratch.local.data();
  int* rel = scratch.pattern.data();
  std::fill(front, front + static_cast<std::size_t>(ld) * w, 0.0);
  for (int q = asm_begin_[s]; q < asm_begin_[s + 1]; ++q) front[asm_dst_[q]] += ax_[asm_src_[q]];
  for (int t = 0; t < w; ++t) local[f + t] = t;
  for (int i = 0; i < m; ++i) local[rows[i]] = w + i;

  // The descendants' updates, in ascending order.
  for (int u = upd_begin_[s]; u < upd_begin_[s + 1]; ++u) {
    const int d = upd_d_[u], p1 = upd_p1_[u], p2 = upd_p2_[u];
    const int fd = sn_first_[d], last = sn_first_[d + 1] - 1, wd = last - fd + 1;
    const int md = lp_[last + 1] - lp_[last], k = p2 - p1, r = md - p1;
    const int* rows_d = li_.data() + lp_[last] + p1;
    const double* ld_rows = ls_.data() + ls_begin_[d] + p1;  // column c at c * md
    const double* pivots = d_.data() + fd;
    for (int i = 0; i < r; ++i) rel[i] = local[rows_d[i]];
    double* work = scratch.update.data();
    if (static_cast<long>(r) * k * wd <= kSmallUpdate) {
      double* scaled = work;   // D_d L_d(row j, :)
      double* column = work + wd;  // the update's column j, rows j .. r - 1
      for (int j = 0; j < k; ++j) {
        for (int c = 0; c < wd; ++c) scaled[c] = pivots[c] * ld_rows[c * md + j];
        std::fill(column + j, column + r, 0.0);
        for (int c = 0; c < wd; ++c) {
          const double v = scaled[c];
          const double* lc = ld_rows + c * md;
          for (int i = j; i < r; ++i) column[i] += lc[i] * v;
        }
        double* target = front + static_cast<std::size_t>(rel[j]) * ld;
        for (int i = j; i < r; ++i) target[rel[i]] -= column[i];
      }
    } else {
      const ConstMatMap lr(ld_rows, r, wd, Strided(md));
      MatMap v(work, k, wd, Strided(k));
      v.noalias() = lr.topRows(k) * ConstVecMap(pivots, wd).asDiagonal();
      MatMap c(work + static_cast<std::size_t>(k) * wd, r, k, Strided(r));
      c.topRows(k).triangularView<Eigen::Lower>() = lr.topRows(k) * v.transpose();
      if (r > k) c.bottomRows(r - k).noalias() = lr.bottomRows(r - k) * v.transpose();
      for (int j = 0; j < k; ++j) {
        double* target = front + static_cast<std::size_t>(rel[j]) * ld;
        const double* cj = c.data() + static_cast<std::size_t>(j) * r;
        for (int i = j; i < r; ++i) target[rel[i]] -= cj[i];
      }
    }
  }

  // Dense LDL^T of the front, kPanel columns at a time: within a panel each column takes
  // the updates of the panel's columns before it, then is scaled by its pivot; the
  // panel then updates every column to its right (lower triangle and rows below).
  double* dk = scratch.pivots.data();
  for (int a = 0; a < w; a += kPanel) {
    const int b = std::min(a + kPanel, w);
    for (int j = a; j < b; ++j) {
      double* fj = front + static_cast<std::size_t>(j) * ld;
      if (j > a) {  // column j -= L(j:, a:j) D L(j, a:j)^T, one matrix-vector product
        double* coef = scratch.panel.data();
        for (int t = a; t < j; ++t) coef[t - a] = dk[t] * front[static_cast<std::size_t>(t) * ld + j];
        const ConstMatMap done(front + static_cast<std::size_t>(a) * ld + j, ld - j, j - a, Strided(ld));
        Eigen::Map<Eigen::VectorXd>(fj + j, ld - j).noalias() -= done * ConstVecMap(coef, j - a);
      }
      const double pivot = fj[j];
      if (!std::isfinite(pivot) || (positive_definite ? !(pivot > 0.0) : pivot == 0.0)) {
        ok = false;
        return;
      }
      dk[j] = pivot;
      const double inverse = 1.0 / pivot;
      for (int i = j + 1; i < ld; ++i) fj[i] *= inverse;
    }
    if (b < w) {
      const int nb = b - a, rest = w - b;
      const ConstMatMap panel(front + static_cast<std::size_t>(a) * ld + b, ld - b, nb, Strided(ld));
      MatMap v(scratch.panel.data(), rest, nb, Strided(rest));
      v.noalias() = panel.topRows(rest) * ConstVecMap(dk + a, nb).asDiagonal();
      MatMap trailing(front + static_cast<std::size_t>(b) * ld + b, ld - b, rest, Strided(ld));
      trailing.topRows(rest).triangularView<Eigen::Lower>() -= panel.topRows(rest) * v.transpose();
      if (m > 0) trailing.bottomRows(m).noalias() -= panel.bottomRows(m) * v.transpose();
    }
  }

  // Into the solves' layout: column f + c holds rows f + c + 1 .. l, then the rows below.
  for (int c = 0; c < w; ++c) {
    d_[f + c] = dk[c];
    const double* fc = front + static_cast<std::size_t>(c) * ld;
    // (A column with no entries below may sit in an empty lx_, whose data() is null.)
    if (const int below = ld - c - 1; below > 0)
      std::memcpy(lx_.data() + lp_[f + c], fc + c + 1, sizeof(double) * below);
    if (m > 0) std::memcpy(ls_.data() + ls_begin_[s] + static_cast<std::size_t>(c) * m, fc + w,
                           sizeof(double) * m);
  }
}

}  // namespace invfree
