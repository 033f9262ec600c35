// Exact LDL^T of a principal submatrix H_DD of a sparse symmetric matrix, for a small index
// set D that changes from one call to the next (PCG's block correction of a reused factor,
// core/linalg/pcg.cpp).
//
// D is ordered by reverse Cuthill-McKee (George & Liu, "Computer Solution of Large Sparse
// Positive Definite Systems", 1981, ch. 4: breadth-first from a pseudo-peripheral node,
// neighbours by increasing degree, then reversed), which keeps the strips of nodes along a
// contact plane, the sets this is made for, within a narrow band; the factor is then the
// envelope (profile) LDL^T of that ordering: row r of L is stored from its first nonzero
// column to the diagonal and fill stays inside it.
//
// Inputs: H in full symmetric CSC storage (both triangles), possibly with couplings outside
// that pattern (2x2 node blocks, both orientations listed), D as a list of distinct row
// indices. Output: solve() applies H_DD^-1. Every buffer is sized by `reserve`; a set or
// an envelope larger than those buffers is refused (factorize returns false), never grown;
// only the couplings' entries, beyond 16 per unknown of the set, grow theirs.
#pragma once

#include <Eigen/SparseCore>
#include <span>
#include <vector>

#include "linalg/node_coupling.h"
#include "types.h"

namespace invfree {

class SubmatrixLdlt {
 public:
  // Buffers for sets of up to max_size of the n unknowns, envelopes of up to max_envelope
  // entries below the diagonal.
  void reserve(int n, int max_size, long max_envelope);
  int max_size() const { return static_cast<int>(order_.size()); }

  // Orders and factorises H restricted to `set`, H = h plus `couplings` (2x2 blocks outside
  // h's pattern, linalg/node_coupling.h; those with both nodes' unknowns in the set count).
  // False when the set or its envelope does not fit the buffers or a pivot is not positive
  // and finite (H_DD not positive definite).
  bool factorize(const Eigen::SparseMatrix<double>& h, std::span<const NodeCoupling> couplings,
                 const std::vector<int>& set);
  bool factorize(const Eigen::SparseMatrix<double>& h, const std::vector<int>& set) {
    return factorize(h, {}, set);
  }

  // x[a] = (H_DD^-1 rhs_D)[a] for a = 0 .. |D| - 1, in the order of the `set` given to
  // factorize; rhs is full length (only its entries in D are read), x at least |D| long.
  void solve(const VecX& rhs, VecX& x);

  int size() const { return m_; }
  long envelope() const { return m_ > 0 ? env_begin_[m_] : 0; }

 private:
  void order(const Eigen::SparseMatrix<double>& h, const std::vector<int>& set);
  void gather_couplings(std::span<const NodeCoupling> couplings);

  int m_ = 0;
  std::vector<int> local_;       // per unknown of H: its place in `set`, or -1
  std::vector<int> order_;       // RCM position -> place in `set`
  std::vector<int> position_;    // place in `set` -> RCM position
  std::vector<int> degree_;      // per place in `set`: neighbours inside the set
  std::vector<int> first_;       // per RCM row: its first column in the envelope
  std::vector<long> env_begin_;  // per RCM row: where its envelope entries start
  std::vector<double> env_, d_, row_, work_;
  std::vector<int> mark_;       // per place in `set`: the breadth-first search that reached it
  std::vector<char> placed_;    // per place in `set`: already in the ordering
  std::vector<int> by_degree_;  // places in `set` by increasing degree
  std::vector<int> trial_;      // a candidate start's search (order() keeps it if deeper)
  std::vector<int> set_;        // the set given to factorize (solve reads it)
  // The couplings' entries inside the set, by row: place in `set` -> (place, value) in
  // extra_col_ / extra_value_[extra_begin_[a] .. extra_begin_[a + 1]). Sized by reserve for
  // 16 entries per place; more grow them (an allocation, rare).
  std::vector<int> extra_begin_, extra_col_;
  std::vector<double> extra_value_;
};

}  // namespace invfree
