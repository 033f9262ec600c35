#include "linalg/submatrix_ldlt.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace invfree {

void SubmatrixLdlt::reserve(int n, int max_size, long max_envelope) {
  local_.assign(n, -1);
  order_.assign(max_size, 0);
  position_.assign(max_size, 0);
  degree_.assign(max_size, 0);
  first_.assign(max_size, 0);
  env_begin_.assign(max_size + 1, 0);
  env_.assign(max_envelope, 0.0);
  d_.assign(max_size, 0.0);
  row_.assign(max_size, 0.0);
  work_.assign(max_size, 0.0);
  mark_.assign(max_size, 0);
  placed_.assign(max_size, 0);
  by_degree_.assign(max_size, 0);
  trial_.assign(max_size, 0);
  set_.clear();
  set_.reserve(max_size);
  extra_begin_.assign(max_size + 1, 0);
  extra_col_.assign(16L * max_size, 0);
  extra_value_.assign(16L * max_size, 0.0);
  m_ = 0;
}

// The couplings' scalar entries whose row and column are both in the set, bucketed by row
// place in list order (local_ is set).
void SubmatrixLdlt::gather_couplings(std::span<const NodeCoupling> couplings) {
  const int m = m_;
  std::fill(extra_begin_.begin(), extra_begin_.begin() + m + 1, 0);
  auto each_entry = [&](auto&& fn) {
    for (const NodeCoupling& c : couplings)
      for (int a = 0; a < 2; ++a) {
        const int r = local_[2 * c.row_node + a];
        if (r < 0) continue;
        for (int b = 0; b < 2; ++b) {
          const int col = local_[2 * c.col_node + b];
          if (col >= 0) fn(r, col, c.block(a, b));
        }
      }
  };
  each_entry([&](int r, int, double) { ++extra_begin_[r + 1]; });
  for (int a = 0; a < m; ++a) extra_begin_[a + 1] += extra_begin_[a];
  const size_t total = static_cast<size_t>(extra_begin_[m]);
  if (total > extra_col_.size()) {
    extra_col_.resize(total);
    extra_value_.resize(total);
  }
  each_entry([&](int r, int col, double value) {
    const int at = extra_begin_[r]++;
    extra_col_[at] = col;
    extra_value_[at] = value;
  });
  for (int a = m; a > 0; --a) extra_begin_[a] = extra_begin_[a - 1];
  extra_begin_[0] = 0;
}

// A node coupled to more than this many others (the ceiling's unknown, pulled by every
// node under it) would widen every level it joins; such nodes go last, where each costs
// one long row of the envelope.
constexpr int kDenseDegree = 32;

// Reverse Cuthill-McKee over the graph of H_DD without its dense nodes, one connected
// component at a time; then the dense nodes.
void SubmatrixLdlt::order(const Eigen::SparseMatrix<double>& h, const std::vector<int>& set) {
  const int m = m_;
  const int* outer = h.outerIndexPtr();
  const int* inner = h.innerIndexPtr();
  for (int a = 0; a < m; ++a) {
    int degree = extra_begin_[a + 1] - extra_begin_[a];
    for (int k = outer[set[a]]; k < outer[set[a] + 1]; ++k)
      if (inner[k] != set[a] && local_[inner[k]] >= 0) ++degree;
    degree_[a] = degree;
    mark_[a] = 0;
    placed_[a] = degree > kDenseDegree;  // ordered last, outside the searches
  }
  auto fewer = [&](int a, int b) {
    return degree_[a] != degree_[b] ? degree_[a] < degree_[b] : a < b;
  };
  // Breadth-first from `start` into into[out ..]: each node's new neighbours by increasing
  // degree. Returns the end and sets the start of the last level and the number of levels.
  int stamp = 0;
  auto search = [&](int start, std::vector<int>& into, int out, int& last_level, int& levels) {
    ++stamp;
    mark_[start] = stamp;
    into[out] = start;
    int begin = out, end = out + 1, tail = out + 1;
    levels = 0;
    while (begin < end) {
      ++levels;
      last_level = begin;
      for (int q = begin; q < end; ++q) {
        const int i = set[into[q]];
        const int from = tail;
        auto visit = [&](int b) {
          if (b >= 0 && mark_[b] != stamp && degree_[b] <= kDenseDegree) {
            mark_[b] = stamp;
            into[tail++] = b;
          }
        };
        for (int k = outer[i]; k < outer[i + 1]; ++k) visit(local_[inner[k]]);
        for (int e = extra_begin_[into[q]]; e < extra_begin_[into[q] + 1]; ++e)
          visit(extra_col_[e]);
        std::sort(into.begin() + from, into.begin() + tail, fewer);
      }
      begin = end;
      end = tail;
    }
    return tail;
  };
  int sparse = 0;
  for (int a = 0; a < m; ++a) sparse += degree_[a] <= kDenseDegree;
  // Each component starts from its least connected node: the first one not yet placed in
  // by_degree_ (a scan of all nodes per component would be quadratic in scattered sets).
  std::iota(by_degree_.begin(), by_degree_.begin() + m, 0);
  std::sort(by_degree_.begin(), by_degree_.begin() + m, fewer);
  int next = 0;
  for (int count = 0; count < sparse;) {
    while (placed_[by_degree_[next]]) ++next;
    const int start = by_degree_[next];
    // A pseudo-peripheral start: the least connected node of the last level, while the
    // search from it goes deeper (tried in trial_, kept only if it does).
    int last = 0, levels = 0;
    const int end = search(start, order_, count, last, levels);
    for (int tries = 0; tries < 4; ++tries) {
      const int candidate = *std::min_element(order_.begin() + last, order_.begin() + end, fewer);
      int candidate_last = 0, candidate_levels = 0;
      search(candidate, trial_, count, candidate_last, candidate_levels);
      if (candidate_levels <= levels) break;
      std::copy(trial_.begin() + count, trial_.begin() + end, order_.begin() + count);
      last = candidate_last;
      levels = candidate_levels;
    }
    for (int q = count; q < end; ++q) placed_[order_[q]] = 1;
    count = end;
  }
  std::reverse(order_.begin(), order_.begin() + sparse);
  for (int a = 0, q = sparse; a < m; ++a)
    if (degree_[a] > kDenseDegree) order_[q++] = a;
  for (int r = 0; r < m; ++r) position_[order_[r]] = r;
}

bool SubmatrixLdlt::factorize(const Eigen::SparseMatrix<double>& h,
                              std::span<const NodeCoupling> couplings,
                              const std::vector<int>& set) {
  m_ = 0;
  if (set.size() > order_.size()) return false;
  set_.assign(set.begin(), set.end());
  m_ = static_cast<int>(set.size());
  const int m = m_;
  for (int a = 0; a < m; ++a) local_[set[a]] = a;
  gather_couplings(couplings);
  order(h, set);
  const int* outer = h.outerIndexPtr();
  const int* inner = h.innerIndexPtr();
  const double* value = h.valuePtr();
  // The envelope: row r from its first neighbour's RCM position to the diagonal.
  env_begin_[0] = 0;
  for (int r = 0; r < m; ++r) {
    const int i = set[order_[r]];
    int first = r;
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const int b = local_[inner[k]];
      if (b >= 0) first = std::min(first, position_[b]);
    }
    for (int e = extra_begin_[order_[r]]; e < extra_begin_[order_[r] + 1]; ++e)
      first = std::min(first, position_[extra_col_[e]]);
    first_[r] = first;
    env_begin_[r + 1] = env_begin_[r] + (r - first);
  }
  bool ok = env_begin_[m] <= static_cast<long>(env_.size());
  if (ok) {
    std::fill(env_.begin(), env_.begin() + env_begin_[m], 0.0);
    for (int r = 0; r < m; ++r) {
      const int i = set[order_[r]];
      d_[r] = 0.0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) {
        const int b = local_[inner[k]];
        if (b < 0) continue;
        const int c = position_[b];
        if (c < r) env_[env_begin_[r] + (c - first_[r])] = value[k];
        if (c == r) d_[r] = value[k];
      }
      // The couplings' entries add (a pair may be listed twice); they are off-diagonal.
      for (int e = extra_begin_[order_[r]]; e < extra_begin_[order_[r] + 1]; ++e) {
        const int c = position_[extra_col_[e]];
        if (c < r) env_[env_begin_[r] + (c - first_[r])] += extra_value_[e];
      }
    }
    // Row by row: u_rc = a_rc - sum_k u_rk l_ck (u_rk = l_rk d_k), l_rc = u_rc / d_c,
    // d_r = a_rr - sum_c u_rc l_rc.
    for (int r = 0; r < m && ok; ++r) {
      const int f = first_[r];
      double* lr = env_.data() + env_begin_[r] - f;  // lr[c], c in [f, r)
      double dr = d_[r];
      for (int c = f; c < r; ++c) {
        const int fc = first_[c];
        const double* lc = env_.data() + env_begin_[c] - fc;
        double s = lr[c];
        for (int k = std::max(f, fc); k < c; ++k) s -= row_[k] * lc[k];
        row_[c] = s;
        lr[c] = s / d_[c];
        dr -= s * lr[c];
      }
      d_[r] = dr;
      ok = std::isfinite(dr) && dr > 0.0;
    }
  }
  for (int a = 0; a < m; ++a) local_[set[a]] = -1;
  if (!ok) m_ = 0;
  return ok;
}

void SubmatrixLdlt::solve(const VecX& rhs, VecX& x) {
  const int m = m_;
  double* y = work_.data();
  for (int r = 0; r < m; ++r) {
    const int f = first_[r];
    const double* lr = env_.data() + env_begin_[r] - f;
    double s = rhs[set_[order_[r]]];
    for (int c = f; c < r; ++c) s -= lr[c] * y[c];
    y[r] = s;
  }
  for (int r = 0; r < m; ++r) y[r] /= d_[r];
  for (int r = m - 1; r >= 0; --r) {
    const int f = first_[r];
    const double* lr = env_.data() + env_begin_[r] - f;
    const double yr = y[r];
    for (int c = f; c < r; ++c) y[c] -= lr[c] * yr;
  }
  for (int r = 0; r < m; ++r) x[order_[r]] = y[r];
}

}  // namespace invfree
