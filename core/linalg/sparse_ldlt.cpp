#include "linalg/sparse_ldlt.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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
// The factorisation's blocks (factor_rows): its rows below a block are y's, in a scratch
// vector that stays in cache, so wider blocks than the solves' still pay.
constexpr int kFactorBlock = 8;

#if defined(__SSE2__)
// Two consecutive entries of a column as doubles. (The SSE2 loops below make the very
// operations of the scalar ones, two rows or two partial sums at a time: the same bits.)
inline __m128d load_pair(const double* p) { return _mm_loadu_pd(p); }
inline __m128d load_pair(const float* p) {
  return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))));
}
#endif

// Forward, L y = b: the block [a, a + W) updates its own rows, then every row below it,
// the first `split` of `rows` in y and the rest in acc, at `slots` (one per row from `split`). Each row gets the columns'
// updates in column order, as a column-by-column loop makes them.
template <int W, class T>
inline void forward_block(int a, int j1, const int* rows, int count, int split, const int* lp,
                          const T* lx, double* y, double* acc, const int* slots) {
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
  int r = 0;
#if defined(__SSE2__)
  for (; r + 2 <= split; r += 2) {
    __m128d t = _mm_set_pd(y[rows[r + 1]], y[rows[r]]);
#pragma GCC unroll 8
    for (int c = 0; c < W; ++c) t = _mm_sub_pd(t, _mm_mul_pd(load_pair(v[c] + r), _mm_set1_pd(yc[c])));
    _mm_storel_pd(y + rows[r], t);
    _mm_storeh_pd(y + rows[r + 1], t);
  }
#endif
  for (; r < split; ++r) {
    double t = y[rows[r]];
#pragma GCC unroll 8
    for (int c = 0; c < W; ++c) t -= v[c][r] * yc[c];
    y[rows[r]] = t;
  }
  for (r = split; r < count; ++r) {
    double t = acc[slots[r - split]];
#pragma GCC unroll 8
    for (int c = 0; c < W; ++c) t -= v[c][r] * yc[c];
    acc[slots[r - split]] = t;
  }
}

// forward_block<w> for a block width known at run time (1 <= w <= W).
template <int W>
inline void factor_block(int w, int a, int j1, const int* rows, int count, const int* lp,
                         const double* lx, double* y) {
  if constexpr (W > 1) {
    if (w < W) return factor_block<W - 1>(w, a, j1, rows, count, lp, lx, y);
  }
  forward_block<W>(a, j1, rows, count, count, lp, lx, y, nullptr, nullptr);
}

// The supernode [j0, j1] in blocks, left to right. rows, count, split: below j1.
template <class T>
inline void supernode_forward(int j0, int j1, const int* rows, int count, int split, const int* lp,
                              const T* lx, double* y, double* acc, const int* slots) {
  for (int a = j0; a <= j1; a += kBlock) {
    switch (std::min(kBlock, j1 - a + 1)) {
      case 1:
        forward_block<1>(a, j1, rows, count, split, lp, lx, y, acc, slots);
        break;
      case 2:
        forward_block<2>(a, j1, rows, count, split, lp, lx, y, acc, slots);
        break;
      case 3:
        forward_block<3>(a, j1, rows, count, split, lp, lx, y, acc, slots);
        break;
      default:
        forward_block<kBlock>(a, j1, rows, count, split, lp, lx, y, acc, slots);
    }
  }
}

// Supernodes at least this wide are solved as dense blocks (dense_forward,
// dense_backward); narrower ones, whose rows below a block of kBlock columns are touched
// once per solve anyway, by indexed updates (supernode_forward, narrow_backward).
constexpr int kDenseMinWidth = kBlock + 1;

// A supernode [j0, j1] (w columns, m rows below j1) as a dense trapezoid: column j's
// entries lx[lp[j] ..] are rows j + 1 .. j1 and then the m rows below, contiguous, so with
// the supernode's part of the solution in a contiguous z (its own w rows, then the m rows
// below), column j0 + k multiplies z[k + 1 ..] without any index. The columns go in blocks
// of W <= 4 from j0 (the last block the remainder): a block's small triangle, then every
// row below it in one pass over z with the W columns' values in registers. Each sum's
// order is fixed by the supernode, and the passes are independent across rows, so they
// vectorise without reordering anything.

// The rows of a block's pass come in chunks of kChunk; each chunk first prefetches the
// next kChunk * W entries that the solve reads after this block (the next block's
// columns: the factor is read in column order forwards, backwards in reverse), since a
// column of a few hundred entries is too short for the hardware prefetcher to catch up.
constexpr int kChunk = 16;
template <class T>
inline void prefetch_span(const T* p, int entries) {
  for (int q = 0; q < entries; q += 64 / static_cast<int>(sizeof(T))) __builtin_prefetch(p + q);
}

// Forward, block [c, c + W) at z[k ..] (k = c - j0), `len` the rows of z after the block.
template <int W, class T>
inline void dense_forward_block(int c, int k, int len, const int* lp, const T* lx,
                                double* __restrict z) {
  double zc[W];
  const T* __restrict v[W];
#pragma GCC unroll 4
  for (int a = 0; a < W; ++a) {
    zc[a] = z[k + a];
#pragma GCC unroll 4
    for (int b = a + 1; b < W; ++b) z[k + b] -= lx[lp[c + a] + (b - a - 1)] * zc[a];
    v[a] = lx + lp[c + a] + (W - 1 - a);
  }
  double* __restrict rest = z + k + W;
  const T* next = lx + lp[c + W];
  for (int r0 = 0; r0 < len; r0 += kChunk) {
    prefetch_span(next + r0 * W, kChunk * W);
    const int r1 = std::min(len, r0 + kChunk);
    for (int r = r0; r < r1; ++r) {
      double t = rest[r];
#pragma GCC unroll 4
      for (int a = 0; a < W; ++a) t -= v[a][r] * zc[a];
      rest[r] = t;
    }
  }
}

// Forward, L y = b, on the supernode [j0, j1]: z = (y[j0 .. j1], 0 for the rows below),
// the blocks, y[j0 .. j1] = z's first w, and one scatter of z's rows below: y[rows[r]] for
// the first `split`, the task's accumulator slots for the rest.
template <class T>
void dense_forward(int j0, int j1, const int* rows, int m, int split, const int* lp, const T* lx,
                   double* y, double* acc, const int* slots, double* __restrict z) {
  const int w = j1 - j0 + 1;
  std::copy(y + j0, y + j1 + 1, z);
  std::fill(z + w, z + w + m, 0.0);
  for (int c = j0; c <= j1; c += kBlock) {
    const int k = c - j0;
    switch (std::min(kBlock, j1 - c + 1)) {
      case 1:
        dense_forward_block<1>(c, k, w + m - k - 1, lp, lx, z);
        break;
      case 2:
        dense_forward_block<2>(c, k, w + m - k - 2, lp, lx, z);
        break;
      case 3:
        dense_forward_block<3>(c, k, w + m - k - 3, lp, lx, z);
        break;
      default:
        dense_forward_block<kBlock>(c, k, w + m - k - kBlock, lp, lx, z);
    }
  }
  std::copy(z, z + w, y + j0);
  const double* below = z + w;
  for (int r = 0; r < split; ++r) y[rows[r]] += below[r];
  for (int r = split; r < m; ++r) acc[slots[r - split]] += below[r];
}

// Backward, block [c, c + W) at z[k ..], every row after it solved: each column's dot
// product with the `len` rows after the block (two interleaved partial sums per column,
// the W columns in one pass), then the block's triangle from its last column down.
template <int W, class T>
inline void dense_backward_block(int c, int k, int len, const int* lp, const T* lx, const double* d,
                                 double* __restrict z) {
  const T* __restrict v[W];
  double s[W][2];
#pragma GCC unroll 4
  for (int a = 0; a < W; ++a) {
    v[a] = lx + lp[c + a] + (W - 1 - a);
    s[a][0] = s[a][1] = 0.0;
  }
  const double* __restrict rest = z + k + W;
  // What the solve reads next: the entries before this block's, downwards.
  const long before = lp[c];
  int r0 = 0;
#if defined(__SSE2__)
  // The same operations with the two partial sums of a column in one register (the
  // compiler leaves this loop scalar).
  __m128d sv[W];
#pragma GCC unroll 4
  for (int a = 0; a < W; ++a) sv[a] = _mm_setzero_pd();
  for (; r0 + kChunk <= len; r0 += kChunk) {
    prefetch_span(lx + std::max(0L, before - static_cast<long>(r0 + kChunk) * W), kChunk * W);
#pragma GCC unroll 2
    for (int r = r0; r < r0 + kChunk; r += 2) {
      const __m128d x = _mm_loadu_pd(rest + r);
#pragma GCC unroll 4
      for (int a = 0; a < W; ++a) sv[a] = _mm_add_pd(sv[a], _mm_mul_pd(load_pair(v[a] + r), x));
    }
  }
#pragma GCC unroll 4
  for (int a = 0; a < W; ++a) {
    _mm_storel_pd(&s[a][0], sv[a]);
    _mm_storeh_pd(&s[a][1], sv[a]);
  }
#else
  for (; r0 + kChunk <= len; r0 += kChunk) {
    prefetch_span(lx + std::max(0L, before - static_cast<long>(r0 + kChunk) * W), kChunk * W);
    for (int r = r0; r < r0 + kChunk; r += 2) {
#pragma GCC unroll 4
      for (int a = 0; a < W; ++a) {
#pragma GCC unroll 2
        for (int l = 0; l < 2; ++l) s[a][l] += v[a][r + l] * rest[r + l];
      }
    }
  }
#endif
  for (int r = r0; r < len; ++r) {
#pragma GCC unroll 4
    for (int a = 0; a < W; ++a) s[a][r & 1] += v[a][r] * rest[r];
  }
#pragma GCC unroll 4
  for (int a = W - 1; a >= 0; --a) {
    double sum = s[a][0] + s[a][1];
#pragma GCC unroll 4
    for (int b = a + 1; b < W; ++b) sum += lx[lp[c + a] + (b - a - 1)] * z[k + b];
    z[k + a] = z[k + a] / d[c + a] - sum;
  }
}

// Backward, D L^T x = y, on the supernode [j0, j1]: z = (y[j0 .. j1], x[rows]) (one
// gather), the blocks from the last down, x[j0 .. j1] = z's first w.
template <class T>
void dense_backward(int j0, int j1, const int* rows, int m, const int* lp, const T* lx,
                    const double* d, double* y, double* __restrict z) {
  const int w = j1 - j0 + 1;
  std::copy(y + j0, y + j1 + 1, z);
  for (int r = 0; r < m; ++r) z[w + r] = y[rows[r]];
  const int tail = (w - 1) % kBlock + 1;  // the last block's width
  for (int c = j1 + 1 - tail; c >= j0; c -= kBlock) {
    const int k = c - j0;
    switch (c + kBlock - 1 > j1 ? tail : kBlock) {
      case 1:
        dense_backward_block<1>(c, k, w + m - k - 1, lp, lx, d, z);
        break;
      case 2:
        dense_backward_block<2>(c, k, w + m - k - 2, lp, lx, d, z);
        break;
      case 3:
        dense_backward_block<3>(c, k, w + m - k - 3, lp, lx, d, z);
        break;
      default:
        dense_backward_block<kBlock>(c, k, w + m - k - kBlock, lp, lx, d, z);
    }
  }
  std::copy(z, z + w, y + j0);
}

// Backward on a narrow supernode [j0, j0 + W) (W <= kBlock): each row below is gathered
// once for all W columns' dot products (two interleaved partial sums per column; one
// column alone takes column_dot's four), then the triangle from the last column down.
template <int W, class T>
inline void narrow_backward(int j0, const int* rows, int m, const int* lp, const T* lx,
                            const double* d, double* y) {
  if constexpr (W == 1) {
    y[j0] = y[j0] / d[j0] - column_dot(m, rows, lx + lp[j0], y);
  } else {
    const T* __restrict v[W];
    double s0[W], s1[W];
#pragma GCC unroll 4
    for (int a = 0; a < W; ++a) {
      v[a] = lx + lp[j0 + a] + (W - 1 - a);
      s0[a] = s1[a] = 0.0;
    }
    int r = 0;
#if defined(__SSE2__)
    __m128d sv[W];
#pragma GCC unroll 4
    for (int a = 0; a < W; ++a) sv[a] = _mm_setzero_pd();
    for (; r + 2 <= m; r += 2) {
      const __m128d x = _mm_set_pd(y[rows[r + 1]], y[rows[r]]);
#pragma GCC unroll 4
      for (int a = 0; a < W; ++a) sv[a] = _mm_add_pd(sv[a], _mm_mul_pd(load_pair(v[a] + r), x));
    }
#pragma GCC unroll 4
    for (int a = 0; a < W; ++a) {
      _mm_storel_pd(s0 + a, sv[a]);
      _mm_storeh_pd(s1 + a, sv[a]);
    }
#else
    for (; r + 2 <= m; r += 2) {
      const double x0 = y[rows[r]], x1 = y[rows[r + 1]];
#pragma GCC unroll 4
      for (int a = 0; a < W; ++a) {
        s0[a] += v[a][r] * x0;
        s1[a] += v[a][r + 1] * x1;
      }
    }
#endif
    if (r < m) {
      const double x0 = y[rows[r]];
#pragma GCC unroll 4
      for (int a = 0; a < W; ++a) s0[a] += v[a][r] * x0;
    }
#pragma GCC unroll 4
    for (int a = W - 1; a >= 0; --a) {
      double s = s0[a] + s1[a];
#pragma GCC unroll 4
      for (int b = a + 1; b < W; ++b) s += lx[lp[j0 + a] + (b - a - 1)] * y[j0 + b];
      y[j0 + a] = y[j0 + a] / d[j0 + a] - s;
    }
  }
}

}  // namespace

void SparseLdlt::analyze(const Eigen::SparseMatrix<double>& pattern,
                         const std::vector<int>& new_to_old, int parts) {
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
  row_factor_work_.assign(n, 1.0);
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    for (int p = ap_[k]; p < ap_[k + 1]; ++p)
      for (int i = ai_[p]; flag[i] != k; i = parent_[i]) {
        row_factor_work_[k] += 2.0 * lnz_[i] + 1.0;  // row k's update from column i
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
  plan(std::max(parts, 1));
  share_row_indices();
  plan_accumulators();
  plan_supernodes();
  scratch_.clear();  // sized for this analysis
  size_scratch();
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
  solve_rows_.clear();
  solve_row_begin_.assign(n, 0);
  snode_last_.assign(n, 0);
  snode_first_.assign(n, 0);
  // Chains do not cross from one task into another (the forward solve handles a
  // supernode at once, and two tasks are solved at different times).
  for (int first = 0; first < n;) {
    int last = first;
    while (last + 1 < n && parent_[last] == last + 1 && count(last) == count(last + 1) + 1 &&
           task_of_[last] == task_of_[last + 1])
      ++last;
    const int base = static_cast<int>(solve_rows_.size());
    solve_rows_.insert(solve_rows_.end(), li_.begin() + lp_[first], li_.begin() + lp_[first + 1]);
    for (int j = first; j <= last; ++j) {
      solve_row_begin_[j] = base + (j - first);
      snode_last_[j] = last;
      snode_first_[j] = first;
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
  // Moves the heaviest candidate's root to the top, its children into the candidates.
  // False (and nothing moved) where that would put more than half the work in the top.
  bool expand(std::vector<int>& cand, std::vector<char>& is_top, double& top_work) const {
    auto it =
        std::min_element(cand.begin(), cand.end(), [this](int a, int b) { return heavier(a, b); });
    const int c = *it;
    if (top_work + w[c] > 0.5 * total) return false;
    top_work += w[c];
    cand.erase(it);
    is_top[c] = 1;
    for (int child : children[c]) cand.push_back(child);
    return true;
  }
  double heaviest(const std::vector<int>& cand) const {
    double m = 0.0;
    for (int c : cand) m = std::max(m, subtree[c]);
    return m;
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

}  // namespace

// The schedule: the tree cut into tasks, each a set of columns whose rows it factorises
// and solves, ordered in levels so that a task only needs tasks of lower levels (its
// columns' descendants) before it and only tasks of higher levels after it in the
// backward solve.
//   Level 0: the subtrees left when the heaviest subtree has been expanded until none
//   holds more than 1/parts of the work (or the expanded columns, the top, would hold
//   half of it), dealt largest-first into `parts` bins.
//   Above: the expanded columns (the top) in chains: a column with exactly one child in
//   the top joins that child's task, any other starts a task; a task's level is one more
//   than the highest of the tasks holding its columns' children.
// The cut depends on the matrix and `parts` alone, never on the thread count.
void SparseLdlt::plan(int parts) {
  const int n = n_;
  const WorkTree t = work_tree(n, lp_, parent_);
  std::vector<int> cand = t.roots;
  std::vector<char> is_top(n, 0);
  double top_work = 0.0;
  if (parts > 1)
    while (!cand.empty() && t.heaviest(cand) > t.total / parts &&
           t.expand(cand, is_top, top_work)) {
    }

  // Level 0: the candidate subtrees in bins, largest first into the lightest bin.
  std::sort(cand.begin(), cand.end(), [&t](int a, int b) { return t.heavier(a, b); });
  const int bins = std::max(1, std::min<int>(parts, static_cast<int>(cand.size())));
  std::vector<double> load(bins, 0.0);
  std::vector<std::vector<std::pair<int, int>>> task_ranges(bins);
  task_of_.assign(n, -1);
  for (int c : cand) {
    const int b = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    load[b] += t.subtree[c];
    task_ranges[b].push_back({t.first[c], c + 1});
    for (int j = t.first[c]; j <= c; ++j) task_of_[j] = b;
  }
  std::vector<int> level(bins, 0);
  std::vector<double> task_work(load);
  // The top in chains, children before parents (postorder).
  for (int j = 0; j < n; ++j) {
    if (!is_top[j]) continue;
    int top_children = 0, only = -1, lvl = 0;
    for (int c : t.children[j]) {
      if (is_top[c]) {
        ++top_children;
        only = c;
      }
    }
    int task;
    if (top_children == 1) {
      task = task_of_[only];
    } else {
      task = static_cast<int>(task_ranges.size());
      task_ranges.emplace_back();
      level.push_back(0);
      task_work.push_back(0.0);
    }
    for (int c : t.children[j])
      if (task_of_[c] != task) lvl = std::max(lvl, level[task_of_[c]] + 1);
    level[task] = std::max(level[task], lvl);
    task_of_[j] = task;
    task_work[task] += t.w[j];
    auto& r = task_ranges[task];
    if (!r.empty() && r.back().second == j)
      ++r.back().second;
    else
      r.push_back({j, j + 1});
  }
  for (auto& r : task_ranges) std::sort(r.begin(), r.end());

  // Number the tasks by level, the heaviest first within a level (claimed first).
  const int tasks = static_cast<int>(task_ranges.size());
  std::vector<int> order(tasks);
  for (int k = 0; k < tasks; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    if (level[a] != level[b]) return level[a] < level[b];
    if (task_work[a] != task_work[b]) return task_work[a] > task_work[b];
    return task_ranges[a].front() < task_ranges[b].front();
  });
  std::vector<int> renumber(tasks);
  for (int k = 0; k < tasks; ++k) renumber[order[k]] = k;
  for (int j = 0; j < n; ++j) task_of_[j] = renumber[task_of_[j]];
  ranges_.clear();
  range_begin_.assign(1, 0);
  level_begin_.assign(1, 0);
  task_work_.assign(tasks, 0.0);
  for (int k = 0; k < tasks; ++k) {
    const int old = order[k];
    ranges_.insert(ranges_.end(), task_ranges[old].begin(), task_ranges[old].end());
    range_begin_.push_back(static_cast<int>(ranges_.size()));
    task_work_[k] = task_work[old];
    if (k > 0 && level[old] != level[order[k - 1]]) level_begin_.push_back(k);
  }
  level_begin_.push_back(tasks);

  // A column's rows are its ancestors: those in its own task come first (an ancestor in
  // another task belongs to a task of a higher level, whose columns are all above it).
  split_.assign(n, 0);
  for (int j = 0; j < n; ++j) {
    int p = lp_[j];
    while (p < lp_[j + 1] && task_of_[li_[p]] == task_of_[j]) ++p;
    split_[j] = p;
  }
  // Fraction of the solve's work in levels of one task, which nothing else overlaps.
  double alone = 0.0;
  for (std::size_t l = 0; l + 1 < level_begin_.size(); ++l)
    if (level_begin_[l + 1] - level_begin_[l] == 1) alone += task_work_[level_begin_[l]];
  serial_fraction_ = t.total > 0.0 && tasks > 1 ? alone / t.total : 0.0;
}

// The forward solve's updates from a task to rows of other tasks go to the task's own
// accumulator slots (one per distinct such row), added to y by the row's task before it
// starts, in task order: every sum has an order fixed by the schedule.
void SparseLdlt::plan_accumulators() {
  const int n = n_;
  const int tasks = static_cast<int>(range_begin_.size()) - 1;
  ext_base_.assign(n, 0);
  ext_slots_.clear();
  acc_begin_.assign(tasks + 1, 0);
  std::vector<int> slot_of(n, -1), seen_in(n, -1);
  std::vector<std::vector<int>> gathers(n);  // per row: the slots that feed it, task order
  int slots = 0;
  for (int task = 0; task < tasks; ++task) {
    acc_begin_[task] = slots;
    for (int r = range_begin_[task]; r < range_begin_[task + 1]; ++r)
      for (int j = ranges_[r].first; j < ranges_[r].second; j = snode_last_[j] + 1) {
        const int last = snode_last_[j];
        const int* rows = solve_rows_.data() + solve_row_begin_[last];
        const int count = lp_[last + 1] - lp_[last], split = split_[last] - lp_[last];
        ext_base_[last] = static_cast<int>(ext_slots_.size());
        for (int q = split; q < count; ++q) {
          const int row = rows[q];
          if (seen_in[row] != task) {
            seen_in[row] = task;
            slot_of[row] = slots++;
            gathers[row].push_back(slot_of[row]);
          }
          ext_slots_.push_back(slot_of[row]);
        }
      }
  }
  acc_begin_[tasks] = slots;
  acc_.assign(slots, 0.0);
  // Each task's scratch for its dense supernodes: the rows below (t) and the columns' dot
  // products, sized for its largest.
  dense_begin_.assign(tasks + 1, 0);
  for (int task = 0; task < tasks; ++task) {
    int need = 0;
    for (int r = range_begin_[task]; r < range_begin_[task + 1]; ++r)
      for (int j = ranges_[r].first; j < ranges_[r].second; j = snode_last_[j] + 1) {
        const int last = snode_last_[j];
        if (last - j + 1 >= kDenseMinWidth)
          need = std::max(need, lp_[last + 1] - lp_[last] + last - j + 1);
      }
    dense_begin_[task + 1] = dense_begin_[task] + need;
  }
  dense_scratch_.assign(dense_begin_[tasks], 0.0);
  gather_begin_.assign(n + 1, 0);
  gather_slots_.clear();
  for (int j = 0; j < n; ++j) {
    gather_slots_.insert(gather_slots_.end(), gathers[j].begin(), gathers[j].end());
    gather_begin_[j + 1] = static_cast<int>(gather_slots_.size());
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
    // The pattern's columns in topological order; a run of consecutive columns of one
    // supernode (up to kBlock) updates the rows below it together (forward_block: the
    // same operations in the same order as one column after another, so the same bits).
    // So far column j holds its rows below j and above k: in a supernode [j0, j1] with
    // j1 < k, rows j + 1 .. j1 and then the first lnz_[j1] of the shared rows below j1;
    // where k lies in the supernode, only rows j + 1 .. k - 1.
    const int* lp = lp_.data();
    if (factor_method_ == FactorMethod::kRowsOneColumnAtATime) {
      for (; head < n; ++head) {
        const int i = pattern[head];
        const double yi = y[i];
        y[i] = 0.0;
        const int p2 = lp[i] + lnz_[i];
        for (int p = lp[i]; p < p2; ++p) y[li_[p]] -= lx_[p] * yi;
        const double l_ki = yi / d_[i];
        dk -= l_ki * yi;
        lx_[p2] = l_ki;
        ++lnz_[i];
      }
    }
    while (head < n) {
      const int i = pattern[head];
      const int last = std::min(snode_last_[i], k - 1);
      int w = 1;
      while (w < kFactorBlock && head + w < n && pattern[head + w] == i + w && i + w <= last) ++w;
      const int below = snode_last_[i] < k ? lnz_[last] : 0;
      const int* rows = solve_rows_.data() + solve_row_begin_[snode_last_[i]];
      const double* lx = lx_.data();
      factor_block<kFactorBlock>(w, i, last, rows, below, lp, lx, y);
      for (int j = i; j < i + w; ++j) {
        const double yj = y[j];
        y[j] = 0.0;
        const double l_kj = yj / d_[j];
        dk -= l_kj * yj;
        lx_[lp[j] + lnz_[j]] = l_kj;
        ++lnz_[j];
      }
      head += w;
    }
    d_[k] = dk;
    if (!std::isfinite(dk) || (positive_definite ? !(dk > 0.0) : dk == 0.0)) ok = false;
  }
}

void SparseLdlt::size_scratch() {
  const int runners = std::clamp(thread_count(), 1, kMaxRunners);
  if (static_cast<int>(scratch_.size()) == runners) return;
  scratch_.assign(runners, Scratch{});
  for (Scratch& s : scratch_) {
    s.y.assign(n_, 0.0);
    s.flag.assign(n_, -1);
    s.pattern.assign(n_, 0);
    s.front.assign(front_size_, 0.0);
    s.update.assign(update_size_, 0.0);
    s.panel.assign(panel_size_, 0.0);
    s.pivots.assign(front_width_, 0.0);
    s.local.assign(n_, 0);
  }
}

bool SparseLdlt::factorize(const Eigen::SparseMatrix<double>& a, bool positive_definite) {
  const double* values = a.valuePtr();
  {  // the permuted copy of the values: a gather of millions of entries at n_seg 256
    const int count = static_cast<int>(source_.size());
    const BlockSplit blocks = split_blocks(count, 1 << 16, 64);
    thread_pool().run(blocks.blocks, [&](int b) {
      for (int k = blocks.begin(b); k < blocks.end(b, count); ++k) ax_[k] = values[source_[k]];
    });
  }
  size_scratch();  // allocates only where the thread count changed since the analysis
  const int runners = static_cast<int>(scratch_.size());
  // Each runner works with its own scratch; marks of an earlier factorisation would stop
  // this one's row walks early.
  char ok_runner[kMaxRunners];
  thread_pool().run(runners, [&](int r) {
    std::fill(scratch_[r].flag.begin(), scratch_[r].flag.end(), -1);
    ok_runner[r] = 1;
  });
  const int levels = static_cast<int>(level_begin_.size()) - 1;
  for (int l = 0; l < levels; ++l) {
    const int first = level_begin_[l], count = level_begin_[l + 1] - first;
    std::atomic<int> next{0};
    thread_pool().run(std::min(runners, count), [&](int r) {
      bool ok = ok_runner[r] != 0;
      for (int k; ok && (k = next.fetch_add(1, std::memory_order_relaxed)) < count;) {
        const int task = first + k;
        for (int q = range_begin_[task]; q < range_begin_[task + 1] && ok; ++q) {
          if (factor_method_ != FactorMethod::kSupernodal) {
            factor_rows(ranges_[q].first, ranges_[q].second, scratch_[r], positive_definite, ok);
            continue;
          }
          for (int j = ranges_[q].first; j < ranges_[q].second && ok; j = snode_last_[j] + 1)
            factor_supernode(sn_of_[j], scratch_[r], positive_definite, ok);
        }
      }
      ok_runner[r] = ok ? 1 : 0;
    });
    bool ok = true;
    for (int r = 0; r < runners; ++r) ok = ok && ok_runner[r];
    if (!ok) return false;
  }
  if (!lx_float_.empty()) {
    // Made once every row is done: row k writes entry k of the columns below it.
    const std::size_t count = lx_.size();
    const BlockSplit blocks = split_blocks(static_cast<int>(count), 1 << 16, 64);
    thread_pool().run(blocks.blocks, [&](int b) {
      for (int k = blocks.begin(b); k < blocks.end(b, static_cast<int>(count)); ++k)
        lx_float_[k] = static_cast<float>(lx_[k]);
    });
  }
  return true;
}

void SparseLdlt::keep_float_copy(bool on) {
  lx_float_.assign(on ? lx_.size() : 0, 0.0f);
  lx_float_.shrink_to_fit();
}

template <class T>
void SparseLdlt::solve_with(const T* lx, const VecX& b, VecX& x) {
  const int n = n_;
  double* y = work_.data();
  double* acc = acc_.data();
  const int* lp = lp_.data();
  // Column j's rows: sr[sb[j]] .. sr[sb[j] + lp[j + 1] - lp[j] - 1] (share_row_indices).
  const int* sb = solve_row_begin_.data();
  const int* sr = solve_rows_.data();
  const int* gb = gather_begin_.data();
  const int* gs = gather_slots_.data();
  const double* d = d_.data();
  // The permutations in fixed blocks over the pool: each writes every entry once (the
  // first as a scatter: on one thread it is faster than the gather, whose reads stall).
  const BlockSplit perm_blocks = split_blocks(n, 1 << 13, 64);
  thread_pool().run(perm_blocks.blocks, [&](int k) {
    for (int i = perm_blocks.begin(k); i < perm_blocks.end(k, n); ++i) y[old_to_new_[i]] = b[i];
  });
  const int levels = static_cast<int>(level_begin_.size()) - 1;
  // Forward: L y = b, level by level; a task first takes the updates its rows received
  // from the tasks below, then updates its own rows in y and the others' in its slots.
  for (int l = 0; l < levels; ++l) {
    const int first = level_begin_[l];
    thread_pool().run(level_begin_[l + 1] - first, [&](int k) {
      const int task = first + k;
      std::fill(acc + acc_begin_[task], acc + acc_begin_[task + 1], 0.0);
      for (int r = range_begin_[task]; r < range_begin_[task + 1]; ++r)
        for (int j = ranges_[r].first; j < ranges_[r].second; ++j) {
          double v = y[j];
          for (int g = gb[j]; g < gb[j + 1]; ++g) v += acc[gs[g]];
          y[j] = v;
        }
      double* scratch = dense_scratch_.data() + dense_begin_[task];
      for (int r = range_begin_[task]; r < range_begin_[task + 1]; ++r)
        for (int j = ranges_[r].first; j < ranges_[r].second; j = snode_last_[j] + 1) {
          const int last = snode_last_[j];
          const int m = lp[last + 1] - lp[last], split = split_[last] - lp[last];
          const int* slots = ext_slots_.data() + ext_base_[last];
          if (last - j + 1 >= kDenseMinWidth)
            dense_forward(j, last, sr + sb[last], m, split, lp, lx, y, acc, slots, scratch);
          else
            supernode_forward(j, last, sr + sb[last], m, split, lp, lx, y, acc, slots);
        }
    });
  }
  // Backward: D L^T x = y, the levels top down; a wide supernode as a dense block
  // (dense_backward), a narrow one a dot product per column in column_dot's fixed order.
  for (int l = levels; l-- > 0;) {
    const int first = level_begin_[l];
    thread_pool().run(level_begin_[l + 1] - first, [&](int k) {
      const int task = first + k;
      double* scratch = dense_scratch_.data() + dense_begin_[task];
      for (int r = range_begin_[task + 1]; r-- > range_begin_[task];)
        for (int last = ranges_[r].second - 1; last >= ranges_[r].first;) {
          const int j0 = snode_first_[last];
          const int* rows = sr + sb[last];
          const int m = lp[last + 1] - lp[last];
          if (last - j0 + 1 >= kDenseMinWidth) {
            dense_backward(j0, last, rows, m, lp, lx, d, y, scratch);
          } else {
            switch (last - j0 + 1) {
              case 1:
                narrow_backward<1>(j0, rows, m, lp, lx, d, y);
                break;
              case 2:
                narrow_backward<2>(j0, rows, m, lp, lx, d, y);
                break;
              case 3:
                narrow_backward<3>(j0, rows, m, lp, lx, d, y);
                break;
              default:
                narrow_backward<kBlock>(j0, rows, m, lp, lx, d, y);
            }
          }
          last = j0 - 1;
        }
    });
  }
  thread_pool().run(perm_blocks.blocks, [&](int k) {
    for (int i = perm_blocks.begin(k); i < perm_blocks.end(k, n); ++i) x[i] = y[old_to_new_[i]];
  });
}

SparseLdlt::TreeParallelism SparseLdlt::tree_parallelism() const {
  TreeParallelism t;
  std::vector<double> factor_path(n_, 0.0), solve_path(n_, 0.0);
  for (int j = 0; j < n_; ++j) {  // postorder: children first
    factor_path[j] += row_factor_work_[j];
    solve_path[j] += 4.0 * (lp_[j + 1] - lp_[j]) + 1.0;
    t.factor_work += row_factor_work_[j];
    t.solve_work += 4.0 * (lp_[j + 1] - lp_[j]) + 1.0;
    t.factor_span = std::max(t.factor_span, factor_path[j]);
    t.solve_span = std::max(t.solve_span, solve_path[j]);
    if (const int p = parent_[j]; p != -1) {
      factor_path[p] = std::max(factor_path[p], factor_path[j]);
      solve_path[p] = std::max(solve_path[p], solve_path[j]);
    }
  }
  return t;
}

double SparseLdlt::schedule_speedup(int threads) const {
  double total = 0.0, time = 0.0;
  for (std::size_t l = 0; l + 1 < level_begin_.size(); ++l) {
    double work = 0.0, largest = 0.0;
    for (int t = level_begin_[l]; t < level_begin_[l + 1]; ++t) {
      work += task_work_[t];
      largest = std::max(largest, task_work_[t]);
    }
    total += work;
    time += std::max(largest, work / std::max(threads, 1));
  }
  return time > 0.0 ? total / time : 1.0;
}

void SparseLdlt::solve(const VecX& b, VecX& x) {
  solve_with(lx_.data(), b, x);
}

void SparseLdlt::solve_float(const VecX& b, VecX& x) {
  if (lx_float_.empty()) return solve(b, x);
  solve_with(lx_float_.data(), b, x);
}

}  // namespace invfree
