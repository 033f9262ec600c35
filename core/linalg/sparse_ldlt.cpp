#include "linalg/sparse_ldlt.h"

#include <algorithm>
#include <cmath>

#include "linalg/parallel.h"

namespace invfree {

namespace {

// Elimination tree of the symmetric matrix whose upper triangle is (ap, ai) (Liu's
// algorithm with path compression). parent[k] = -1 for a root.
void elimination_tree(int n, const std::vector<int>& ap, const std::vector<int>& ai,
                      std::vector<int>& parent) {
  std::vector<int> ancestor(n, -1);
  parent.assign(n, -1);
  for (int k = 0; k < n; ++k)
    for (int p = ap[k]; p < ap[k + 1]; ++p)
      for (int i = ai[p]; i != -1 && i < k;) {
        const int next = ancestor[i];
        ancestor[i] = k;
        if (next == -1) parent[i] = k;
        i = next;
      }
}

// Upper triangle of P A P^T (old_to_new: P) with sorted rows; source[k] is the position
// of entry k in A's value array.
void permuted_upper(const Eigen::SparseMatrix<double>& a, const std::vector<int>& old_to_new,
                    std::vector<int>& ap, std::vector<int>& ai, std::vector<int>& source) {
  const int n = static_cast<int>(a.rows());
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  ap.assign(n + 1, 0);
  for (int col = 0; col < n; ++col)
    for (int k = outer[col]; k < outer[col + 1]; ++k) {
      const int i = old_to_new[inner[k]], j = old_to_new[col];
      if (i <= j) ++ap[j + 1];
    }
  for (int j = 0; j < n; ++j) ap[j + 1] += ap[j];
  std::vector<std::pair<int, int>> entries(ap[n]);
  std::vector<int> fill(ap.begin(), ap.end() - 1);
  for (int col = 0; col < n; ++col)
    for (int k = outer[col]; k < outer[col + 1]; ++k) {
      const int i = old_to_new[inner[k]], j = old_to_new[col];
      if (i <= j) entries[fill[j]++] = {i, k};
    }
  ai.resize(ap[n]);
  source.resize(ap[n]);
  for (int j = 0; j < n; ++j) {
    std::sort(entries.begin() + ap[j], entries.begin() + ap[j + 1]);
    for (int p = ap[j]; p < ap[j + 1]; ++p) {
      ai[p] = entries[p].first;
      source[p] = entries[p].second;
    }
  }
}

// sum_p lx[p] y[li[p]] over [0, end) in four interleaved partial sums: one running
// sum would wait for every multiply-add in turn (the backward solve's bottleneck). The
// order is fixed, so the result does not depend on anything but the factor.
template <class T>
inline double column_dot(int end, const int* li, const T* lx, const double* y) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  int p = 0;
  for (; p + 4 <= end; p += 4) {
    s0 += lx[p] * y[li[p]];
    s1 += lx[p + 1] * y[li[p + 1]];
    s2 += lx[p + 2] * y[li[p + 2]];
    s3 += lx[p + 3] * y[li[p + 3]];
  }
  for (; p < end; ++p) s0 += lx[p] * y[li[p]];
  return (s0 + s1) + (s2 + s3);
}

// The forward solve goes supernode by supernode (a chain j0..j1 whose columns share the
// rows below j1, share_row_indices), a block of at most kBlock columns at a time: every
// row a block touches is read and written once for all its columns, instead of once per
// column, with the very operations a column loop makes. In a fundamental supernode the
// block [a, b] and the columns after it share the rows b + 1 .. j1 (consecutive) and
// then the rows below j1 (`rows`, `count`); column c's entries from row b + 1 on start
// at lx[lp[c] + b - c]. (The loops over a block's columns are unrolled so that its
// pointers and values stay in registers.)
constexpr int kBlock = 4;

// Forward, L y = b: the block [a, a + W) updates its own rows, then every row below it,
// the first `split` of `rows` in y and the rest in acc. Each row gets the columns'
// updates in column order, as a column-by-column loop makes them.
template <int W, class T>
inline void forward_block(int a, int j1, const int* rows, int count, int split, const int* lp,
                          const T* lx, double* y, double* acc) {
  const int b = a + W - 1;
  const T* v[W];
  double yc[W];
#pragma GCC unroll 8
  for (int c = 0; c < W; ++c) {
    const int j = a + c;
    yc[c] = y[j];
    for (int q = 0; q < b - j; ++q) y[j + 1 + q] -= lx[lp[j] + q] * yc[c];
    v[c] = lx + lp[j] + (b - j);
  }
  const int inner = j1 - b;
  for (int q = 0; q < inner; ++q) {
    double t = y[b + 1 + q];
#pragma GCC unroll 8
    for (int c = 0; c < W; ++c) t -= v[c][q] * yc[c];
    y[b + 1 + q] = t;
  }
#pragma GCC unroll 8
  for (int c = 0; c < W; ++c) v[c] += inner;
  auto rows_into = [&](double* target, int begin, int end) {
    for (int r = begin; r < end; ++r) {
      double t = target[rows[r]];
#pragma GCC unroll 8
      for (int c = 0; c < W; ++c) t -= v[c][r] * yc[c];
      target[rows[r]] = t;
    }
  };
  rows_into(y, 0, split);
  rows_into(acc, split, count);
}

// The supernode [j0, j1] in blocks, left to right. rows, count, split: below j1.
template <class T>
inline void supernode_forward(int j0, int j1, const int* rows, int count, int split, const int* lp,
                              const T* lx, double* y, double* acc) {
  for (int a = j0; a <= j1; a += kBlock) {
    switch (std::min(kBlock, j1 - a + 1)) {
      case 1:
        forward_block<1>(a, j1, rows, count, split, lp, lx, y, acc);
        break;
      case 2:
        forward_block<2>(a, j1, rows, count, split, lp, lx, y, acc);
        break;
      case 3:
        forward_block<3>(a, j1, rows, count, split, lp, lx, y, acc);
        break;
      default:
        forward_block<kBlock>(a, j1, rows, count, split, lp, lx, y, acc);
    }
  }
}

}  // namespace

void SparseLdlt::analyze(const Eigen::SparseMatrix<double>& pattern,
                         const std::vector<int>& new_to_old, int bins) {
  n_ = static_cast<int>(pattern.rows());
  const int n = n_;
  // Postorder the elimination tree of the given ordering: same fill, subtrees contiguous.
  old_to_new_.assign(n, 0);
  for (int k = 0; k < n; ++k) old_to_new_[new_to_old[k]] = k;
  permuted_upper(pattern, old_to_new_, ap_, ai_, source_);
  elimination_tree(n, ap_, ai_, parent_);
  std::vector<int> child_begin(n + 2, 0), children(n);
  for (int k = 0; k < n; ++k) ++child_begin[(parent_[k] == -1 ? n : parent_[k]) + 1];
  for (int k = 0; k <= n; ++k) child_begin[k + 1] += child_begin[k];
  {
    std::vector<int> fill(child_begin.begin(), child_begin.end() - 1);
    for (int k = 0; k < n; ++k) children[fill[parent_[k] == -1 ? n : parent_[k]]++] = k;
  }
  std::vector<int> post;  // post[new position] = node of the given ordering
  post.reserve(n);
  std::vector<std::pair<int, int>> stack;  // (node, next child slot); n = virtual root
  stack.push_back({n, child_begin[n]});
  while (!stack.empty()) {
    auto& [node, next] = stack.back();
    if (next < child_begin[node + 1]) {
      const int c = children[next++];
      stack.push_back({c, child_begin[c]});
    } else {
      if (node != n) post.push_back(node);
      stack.pop_back();
    }
  }
  for (int k = 0; k < n; ++k) old_to_new_[new_to_old[post[k]]] = k;
  permuted_upper(pattern, old_to_new_, ap_, ai_, source_);
  elimination_tree(n, ap_, ai_, parent_);
  ax_.assign(ap_.size() ? ap_[n] : 0, 0.0);

  // Symbolic factor: column counts, then the row indices in the order the numeric
  // factorisation writes them (rows ascending).
  lnz_.assign(n, 0);
  std::vector<int> flag(n, -1);
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    for (int p = ap_[k]; p < ap_[k + 1]; ++p)
      for (int i = ai_[p]; flag[i] != k; i = parent_[i]) {
        ++lnz_[i];
        flag[i] = k;
      }
  }
  lp_.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) lp_[k + 1] = lp_[k] + lnz_[k];
  li_.assign(lp_[n], 0);
  lx_.assign(lp_[n], 0.0);
  d_.assign(n, 0.0);
  std::fill(lnz_.begin(), lnz_.end(), 0);
  std::fill(flag.begin(), flag.end(), -1);
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    for (int p = ap_[k]; p < ap_[k + 1]; ++p)
      for (int i = ai_[p]; flag[i] != k; i = parent_[i]) {
        li_[lp_[i] + lnz_[i]++] = k;
        flag[i] = k;
      }
  }
  factor_flops_ = solve_flops_ = 0.0;
  for (int k = 0; k < n; ++k) {
    const double c = lp_[k + 1] - lp_[k];
    factor_flops_ += c * c + c;
    solve_flops_ += 4.0 * c + 1.0;
  }
  plan(std::clamp(bins, 1, 64));
  share_row_indices();
  work_.resize(n);
  if (!lx_float_.empty()) keep_float_copy(true);  // a kept copy follows the new factor's size
}

// Where the solves read each column's row indices. In a chain j, j + 1, ..., last where
// every column's parent is the next and column j has exactly one row more than j + 1
// (a fundamental supernode, Liu, Ng & Peyton 1993), rows(j) = {j + 1} + rows(j + 1): every
// column's rows are a suffix of the first column's. Storing only the first columns' lists
// takes the index traffic of a solve from 4 bytes per entry of L to ~4 per supernode row,
// while the values and the order of every operation stay exactly as they are.
void SparseLdlt::share_row_indices() {
  const int n = n_;
  auto count = [&](int j) { return lp_[j + 1] - lp_[j]; };
  std::vector<char> is_top(n, 0);
  for (int t : top_) is_top[t] = 1;
  solve_rows_.clear();
  solve_row_begin_.assign(n, 0);
  snode_last_.assign(n, 0);
  // Chains do not cross from a bin's subtree into the top (the forward solve handles a
  // supernode at once, and the two are solved at different times).
  for (int first = 0; first < n;) {
    int last = first;
    while (last + 1 < n && parent_[last] == last + 1 && count(last) == count(last + 1) + 1 &&
           is_top[last] == is_top[last + 1])
      ++last;
    const int base = static_cast<int>(solve_rows_.size());
    solve_rows_.insert(solve_rows_.end(), li_.begin() + lp_[first], li_.begin() + lp_[first + 1]);
    for (int j = first; j <= last; ++j) {
      solve_row_begin_[j] = base + (j - first);
      snode_last_[j] = last;
    }
    first = last + 1;
  }
  solve_rows_.shrink_to_fit();
}

namespace {

// The postordered elimination tree with each column's work (its share of one solve) and
// its subtree's, the first column of each subtree, and the children of each column.
struct WorkTree {
  std::vector<double> w, subtree;
  std::vector<int> first;
  std::vector<std::vector<int>> children;
  std::vector<int> roots;
  double total = 0.0;

  bool heavier(int a, int b) const {
    return subtree[a] != subtree[b] ? subtree[a] > subtree[b] : a < b;
  }
  // Largest-first assignment of the candidate subtrees to bins; returns the largest bin.
  double assign(std::vector<int> cand, int bins, std::vector<int>* owner) const {
    std::sort(cand.begin(), cand.end(), [this](int a, int b) { return heavier(a, b); });
    std::vector<double> load(bins, 0.0);
    for (int c : cand) {
      const int b = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
      load[b] += subtree[c];
      if (owner) owner->push_back(b);
    }
    return *std::max_element(load.begin(), load.end());
  }
  // Moves the heaviest candidate's root to the top, its children into the candidates.
  void expand(std::vector<int>& cand, double& top_work) const {
    auto it =
        std::min_element(cand.begin(), cand.end(), [this](int a, int b) { return heavier(a, b); });
    const int c = *it;
    cand.erase(it);
    top_work += w[c];
    for (int child : children[c]) cand.push_back(child);
  }
};

WorkTree work_tree(int n, const std::vector<int>& lp, const std::vector<int>& parent) {
  WorkTree t;
  t.w.resize(n);
  t.subtree.resize(n);
  t.first.resize(n);
  for (int j = 0; j < n; ++j) {
    t.w[j] = 2.0 * (lp[j + 1] - lp[j]) + 1.0;
    t.subtree[j] = t.w[j];
    t.first[j] = j;
  }
  for (int j = 0; j < n; ++j)  // postorder: every child before its parent
    if (parent[j] != -1) {
      t.subtree[parent[j]] += t.subtree[j];
      t.first[parent[j]] = std::min(t.first[parent[j]], t.first[j]);
    }
  t.children.resize(n);
  for (int j = 0; j < n; ++j) (parent[j] == -1 ? t.roots : t.children[parent[j]]).push_back(j);
  for (int r : t.roots) t.total += t.subtree[r];
  return t;
}

// How many expansions of the heaviest subtree minimise (serial top work) + (largest bin's
// work), trying up to 4n while the top holds at most half the work.
int best_expansions(const WorkTree& t, int bins, int n) {
  if (bins == 1) return 0;
  std::vector<int> cand = t.roots;
  double top_work = 0.0;
  int best_steps = 0;
  double best_cost = t.assign(cand, bins, nullptr);
  for (int step = 1; step <= 4 * n && !cand.empty(); ++step) {
    t.expand(cand, top_work);
    if (top_work > 0.5 * t.total) break;
    const double cost = top_work + t.assign(cand, bins, nullptr);
    if (cost < best_cost) {
      best_cost = cost;
      best_steps = step;
    }
  }
  return best_steps;
}

}  // namespace

// Cuts the postordered tree into a top and disjoint subtrees over `bins` bins,
// minimising (serial top work) + (largest bin's work) over successive expansions of the
// heaviest subtree; work = a column's share of one solve.
void SparseLdlt::plan(int bins) {
  const int n = n_;
  const WorkTree t = work_tree(n, lp_, parent_);
  const int best_steps = best_expansions(t, bins, n);
  std::vector<int> cand = t.roots;
  double top_work = 0.0;
  for (int step = 0; step < best_steps; ++step) t.expand(cand, top_work);
  serial_fraction_ = t.total > 0.0 ? top_work / t.total : 0.0;
  const std::vector<int>& first = t.first;

  std::sort(cand.begin(), cand.end(), [&t](int a, int b) { return t.heavier(a, b); });
  std::vector<int> owner;
  t.assign(cand, bins, &owner);
  std::vector<std::vector<std::pair<int, int>>> per_bin(bins);
  std::vector<char> is_top(n, 1);
  for (std::size_t k = 0; k < cand.size(); ++k) {
    const int c = cand[k];
    per_bin[owner[k]].push_back({first[c], c + 1});
    for (int j = first[c]; j <= c; ++j) is_top[j] = 0;
  }
  ranges_.clear();
  range_begin_.assign(1, 0);
  for (auto& r : per_bin) {
    std::sort(r.begin(), r.end());
    ranges_.insert(ranges_.end(), r.begin(), r.end());
    range_begin_.push_back(static_cast<int>(ranges_.size()));
  }
  top_.clear();
  for (int j = 0; j < n; ++j)
    if (is_top[j]) top_.push_back(j);
  // A column's rows are its ancestors: those in its own subtree come first (they are
  // numbered below the subtree's root), the top ones after.
  split_.assign(n, 0);
  for (int j = 0; j < n; ++j) {
    int p = lp_[j];
    while (p < lp_[j + 1] && !is_top[li_[p]]) ++p;
    split_[j] = p;
  }
  scratch_.assign(bins, Scratch{});
  for (Scratch& s : scratch_) {
    s.y.assign(n, 0.0);
    s.acc.assign(n, 0.0);
    s.flag.assign(n, -1);
    s.pattern.assign(n, 0);
  }
}

// Rows [begin, end) of the up-looking factorisation (Davis 2005, ldl_numeric).
void SparseLdlt::factor_rows(int begin, int end, Scratch& s, bool positive_definite, bool& ok) {
  double* y = s.y.data();
  int* flag = s.flag.data();
  int* pattern = s.pattern.data();
  const int n = n_;
  for (int k = begin; k < end && ok; ++k) {
    y[k] = 0.0;
    int head = n;
    flag[k] = k;
    lnz_[k] = 0;
    for (int p = ap_[k]; p < ap_[k + 1]; ++p) {
      int i = ai_[p];
      y[i] += ax_[p];
      int len = 0;
      for (; flag[i] != k; i = parent_[i]) {
        pattern[len++] = i;
        flag[i] = k;
      }
      while (len > 0) pattern[--head] = pattern[--len];
    }
    double dk = y[k];
    y[k] = 0.0;
    for (; head < n; ++head) {
      const int i = pattern[head];
      const double yi = y[i];
      y[i] = 0.0;
      const int p2 = lp_[i] + lnz_[i];
      for (int p = lp_[i]; p < p2; ++p) y[li_[p]] -= lx_[p] * yi;
      const double l_ki = yi / d_[i];
      dk -= l_ki * yi;
      lx_[p2] = l_ki;
      ++lnz_[i];
    }
    d_[k] = dk;
    if (!std::isfinite(dk) || (positive_definite ? !(dk > 0.0) : dk == 0.0)) ok = false;
  }
}

bool SparseLdlt::factorize(const Eigen::SparseMatrix<double>& a, bool positive_definite) {
  const double* values = a.valuePtr();
  for (std::size_t k = 0; k < source_.size(); ++k) ax_[k] = values[source_[k]];
  const int bins = static_cast<int>(scratch_.size());
  bool ok_bin[64];
  thread_pool().run(bins, [&](int b) {
    ok_bin[b] = true;
    // Marks of an earlier factorisation would stop this one's row walks early.
    std::fill(scratch_[b].flag.begin(), scratch_[b].flag.end(), -1);
    for (int r = range_begin_[b]; r < range_begin_[b + 1]; ++r)
      factor_rows(ranges_[r].first, ranges_[r].second, scratch_[b], positive_definite, ok_bin[b]);
  });
  bool ok = true;
  for (int b = 0; b < bins; ++b) ok = ok && ok_bin[b];
  for (std::size_t t = 0; t < top_.size() && ok; ++t)
    factor_rows(top_[t], top_[t] + 1, scratch_[0], positive_definite, ok);
  if (ok && !lx_float_.empty()) {
    // Made once every row is done: row k writes entry k of the columns below it.
    const std::size_t count = lx_.size();
    const BlockSplit blocks = split_blocks(static_cast<int>(count), 1 << 16, 64);
    thread_pool().run(blocks.blocks, [&](int b) {
      for (int k = blocks.begin(b); k < blocks.end(b, static_cast<int>(count)); ++k)
        lx_float_[k] = static_cast<float>(lx_[k]);
    });
  }
  return ok;
}

void SparseLdlt::keep_float_copy(bool on) {
  lx_float_.assign(on ? lx_.size() : 0, 0.0f);
  lx_float_.shrink_to_fit();
}

template <class T>
void SparseLdlt::solve_with(const T* lx, const VecX& b, VecX& x) {
  const int n = n_;
  double* y = work_.data();
  const int* lp = lp_.data();
  // Column j's rows: sr[sb[j]] .. sr[sb[j] + lp[j + 1] - lp[j] - 1] (share_row_indices).
  const int* sb = solve_row_begin_.data();
  const int* sr = solve_rows_.data();
  const double* d = d_.data();
  for (int i = 0; i < n; ++i) y[old_to_new_[i]] = b[i];
  const int bins = static_cast<int>(scratch_.size());
  // Forward: L y = b, the subtrees per bin, then the top.
  thread_pool().run(bins, [&](int bin) {
    double* acc = scratch_[bin].acc.data();
    for (int r = range_begin_[bin]; r < range_begin_[bin + 1]; ++r)
      for (int j = ranges_[r].first; j < ranges_[r].second; j = snode_last_[j] + 1) {
        const int last = snode_last_[j];
        supernode_forward(j, last, sr + sb[last], lp[last + 1] - lp[last], split_[last] - lp[last],
                          lp, lx, y, acc);
      }
  });
  for (int t : top_) {
    double v = y[t];
    for (Scratch& s : scratch_) {
      v += s.acc[t];
      s.acc[t] = 0.0;
    }
    y[t] = v;
  }
  for (std::size_t k = 0; k < top_.size();) {
    const int t = top_[k], last = snode_last_[t];
    const int count = lp[last + 1] - lp[last];
    supernode_forward(t, last, sr + sb[last], count, count, lp, lx, y, nullptr);
    k += static_cast<std::size_t>(last - t + 1);
  }
  // Backward: D L^T x = y, the top first, then the subtrees per bin.
  // Column by column, each a dot product in column_dot's fixed order. (Summing a
  // supernode block's dot products in one pass, as the forward solve's updates are, would
  // be faster but changes the rounding, and n_seg 256's fold steps are sensitive to
  // rounding: see docs/performance.md, "The fold steps at n_seg 256".)
  for (auto it = top_.rbegin(); it != top_.rend(); ++it) {
    const int t = *it;
    y[t] = y[t] / d[t] - column_dot(lp[t + 1] - lp[t], sr + sb[t], lx + lp[t], y);
  }
  thread_pool().run(bins, [&](int bin) {
    for (int r = range_begin_[bin + 1]; r-- > range_begin_[bin];)
      for (int j = ranges_[r].second; j-- > ranges_[r].first;)
        y[j] = y[j] / d[j] - column_dot(lp[j + 1] - lp[j], sr + sb[j], lx + lp[j], y);
  });
  for (int i = 0; i < n; ++i) x[i] = y[old_to_new_[i]];
}

void SparseLdlt::solve(const VecX& b, VecX& x) {
  solve_with(lx_.data(), b, x);
}

void SparseLdlt::solve_float(const VecX& b, VecX& x) {
  if (lx_float_.empty()) return solve(b, x);
  solve_with(lx_float_.data(), b, x);
}

}  // namespace invfree
