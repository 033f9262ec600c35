// Sparse LDL^T factorisation and solves of a symmetric positive definite matrix, split
// over threads along the elimination tree.
//
// The factor is the classic up-looking one (Davis, "Algorithm 849: a concise sparse
// Cholesky factorization package", ACM TOMS 2005): row k of L is a sparse triangular
// solve with the rows above it, D(k) what remains on the diagonal. Two rows whose
// elimination-tree subtrees are disjoint never touch the same column of L, and a column
// of L only holds rows that are its ancestors. So after a postorder (every subtree is a
// contiguous range of columns) the tree is cut into a "top" (closed under ancestors,
// done by one thread after the rest) and disjoint subtrees spread over a fixed number of
// bins. The bins factorise their rows, and run their part of the forward and backward
// solves, concurrently; the forward solve's updates to top rows go to a per-bin
// accumulator added in bin order. Every sum is formed in an order fixed by the matrix
// alone, so the result is bit-identical for any number of threads.
//
// A 2D mesh ordered by nested dissection (or AMD) has a tree whose top separator is a
// few dozen nodes: on the 2-core machines the solves PCG repeats run ~1.8x faster than on
// one thread (`INVFREE_THREADS=1` against 2, `invfree_bench --benchmark_filter=LdltSolve`).
//
// The solves, which PCG repeats many times per factorisation and which are bound by
// memory traffic, read one list of row indices per fundamental supernode instead of one
// per column, and the forward solve works on blocks of up to four of a supernode's
// columns, reading and writing each row below a block once. The values and the order of
// every operation are those of a column-by-column solve, so are the bits.
//
// Inputs: the full symmetric pattern (CSC, both triangles, sorted) and a fill-reducing
// ordering; then values on that same pattern. No allocation after `analyze`.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "types.h"

namespace invfree {

class SparseLdlt {
 public:
  // new_to_old: a fill-reducing ordering of the pattern's rows; it is postordered here.
  // bins: how many independent parts to cut the tree into (1: serial).
  void analyze(const Eigen::SparseMatrix<double>& pattern, const std::vector<int>& new_to_old,
               int bins);
  // Numeric factorisation of `a` (same pattern as analysed). False when a pivot is not
  // finite or zero, or (with `positive_definite`) not positive. Without it an indefinite
  // matrix with nonzero pivots factorises (an exact, unprojected Hessian).
  bool factorize(const Eigen::SparseMatrix<double>& a, bool positive_definite = true);
  // x = A^-1 b, in the original ordering. x may not alias b.
  void solve(const VecX& b, VecX& x);
  // With `keep_float_copy(true)`, every factorisation also stores L rounded to float
  // (arithmetic stays double), and solve_float reads that: half the memory traffic of a
  // solve, for a preconditioner. Without the copy solve_float is solve.
  void keep_float_copy(bool on);
  void solve_float(const VecX& b, VecX& x);

  int size() const { return n_; }
  long factor_nonzeros() const { return static_cast<long>(li_.size()); }
  // Work estimates (flops) from the symbolic factor, for cost models.
  double factor_flops() const { return factor_flops_; }
  double solve_flops() const { return solve_flops_; }
  // Row indices the solves read (one list per supernode, see share_row_indices).
  long solve_row_indices() const { return static_cast<long>(solve_rows_.size()); }
  // Fraction of the solve's work left to the serial top of the tree (0 with one bin).
  double serial_fraction() const { return serial_fraction_; }
  const std::vector<int>& old_to_new() const { return old_to_new_; }

 private:
  struct Scratch {
    std::vector<double> y, acc;
    std::vector<int> flag, pattern;
  };
  void factor_rows(int begin, int end, Scratch& s, bool positive_definite, bool& ok);
  void plan(int bins);
  void share_row_indices();
  template <class T>
  void solve_with(const T* lx, const VecX& b, VecX& x);

  int n_ = 0;
  std::vector<int> old_to_new_;
  // The permuted upper triangle of A: column k holds rows i <= k; value k comes from the
  // caller's value array at source_[k].
  std::vector<int> ap_, ai_, source_;
  std::vector<double> ax_;
  // The factor: L strictly lower, column-major; D.
  std::vector<int> parent_, lp_, li_, lnz_;
  std::vector<double> lx_, d_;
  std::vector<float> lx_float_;  // see keep_float_copy
  // The plan: bin b owns the column ranges ranges_[range_begin_[b] .. range_begin_[b+1])
  // (each [first, last+1)); top_ holds the remaining columns, ascending. split_[j] is the
  // first entry of column j that lies in a top row.
  std::vector<int> range_begin_;
  std::vector<std::pair<int, int>> ranges_;
  std::vector<int> top_, split_;
  std::vector<Scratch> scratch_;
  // The solves' row indices: column j's are solve_rows_[solve_row_begin_[j] ..], one list
  // per supernode (share_row_indices).
  std::vector<int> solve_rows_, solve_row_begin_;
  std::vector<int> snode_last_;  // per column: the last column of its supernode
  VecX work_;
  double factor_flops_ = 0.0, solve_flops_ = 0.0, serial_fraction_ = 0.0;
};

}  // namespace invfree
