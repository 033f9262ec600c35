// Sparse LDL^T factorisation and solves of a symmetric positive definite matrix, spread
// over threads along the elimination tree.
//
// The factor is the classic up-looking one (Davis, "Algorithm 849: a concise sparse
// Cholesky factorization package", ACM TOMS 2005): row k of L is a sparse triangular
// solve with the rows above it, D(k) what remains on the diagonal. Row k needs only the
// rows of its elimination-tree subtree, and column j of L holds only rows that are its
// ancestors. So after a postorder (every subtree a contiguous range of columns) the tree
// is cut into tasks in levels (plan): level 0 holds the subtrees below a cut, dealt into
// `parts` bins of equal work, and each level above the chains of the tree's top whose
// children all lie in lower levels. The tasks of a level run concurrently on any number
// of threads: they factorise their rows, and run their part of the forward solve (levels
// upwards) and the backward solve (downwards). A task's forward updates to rows of other
// tasks go to its own accumulator slots, which each row adds in task order before its
// task starts. Every sum is thus formed in an order fixed by the matrix and `parts`, never
// by the thread count: the result is bit-identical for 1, 2 or N threads.
//
// A 2D mesh ordered by nested dissection has a tree whose top separators are a few dozen
// to a few hundred unknowns: one solve's work is ~11x its span (the heaviest root-to-leaf
// path) at n_seg 256, the factorisation's only ~1.6x (its top rows are long sparse
// solves); `invfree_bench --benchmark_filter=LdltSolve` prints both ratios
// (tree_parallelism below).
//
// The solves, which PCG repeats many times per factorisation, read one list of row
// indices per fundamental supernode. A supernode of five or more columns is a dense
// trapezoid (its columns contiguous in L): the forward solve copies its rows and zeros
// for the rows below into a contiguous buffer, updates it in blocks of four columns
// (vectorised passes, no indices) and scatters the rows below once into y and the task's
// accumulator slots; the backward solve gathers the rows below once and takes every
// column's dot product with the buffer. Narrower supernodes update the rows below a block
// of up to four columns directly, reading each once. Where the compiler leaves a loop
// scalar (the backward dot products, the narrow supernodes' indexed rows), SSE2 takes two
// rows or two partial sums at a time with the scalar loop's very operations: the same bits
// with or without it. Each sum's order is fixed by the supernodes and `parts`, so the
// solve stays bit-identical for any thread count. The permutations in and out run in
// fixed blocks over the threads.
//
// Inputs: the full symmetric pattern (CSC, both triangles, sorted) and a fill-reducing
// ordering; then values on that same pattern. No allocation after `analyze` (unless the
// thread count changes: each thread factorises with its own scratch).
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "types.h"

namespace invfree {

class SparseLdlt {
 public:
  // new_to_old: a fill-reducing ordering of the pattern's rows; it is postordered here.
  // parts: how many bins of independent subtrees the tree's bottom is cut into (1: one
  // task, serial). It fixes the rounding of the solves, so it must not depend on the
  // thread count.
  void analyze(const Eigen::SparseMatrix<double>& pattern, const std::vector<int>& new_to_old,
               int parts);
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
  // How factorize works. kSupernodal (the default): left-looking by supernode with dense
  // kernels (sparse_ldlt_supernodal.cpp). kRows: the up-looking rows, in supernode blocks;
  // kRowsOneColumnAtATime: the same rows one column at a time (the same operations in the
  // same order as kRows, so the same bits; for tests). All three give the same pattern and
  // layout of L; the supernodal factor's rounding differs from the rows'.
  enum class FactorMethod { kSupernodal, kRows, kRowsOneColumnAtATime };
  void set_factor_method(FactorMethod m) { factor_method_ = m; }
  void solve_float(const VecX& b, VecX& x);

  int size() const { return n_; }
  long factor_nonzeros() const { return static_cast<long>(li_.size()); }
  // Work estimates (flops) from the symbolic factor, for cost models.
  double factor_flops() const { return factor_flops_; }
  double solve_flops() const { return solve_flops_; }
  // Row indices the solves read (one list per supernode, see share_row_indices).
  long solve_row_indices() const { return static_cast<long>(solve_rows_.size()); }
  // Fraction of the solve's work in levels of a single task, which no other work overlaps
  // (0 with one part).
  double serial_fraction() const { return serial_fraction_; }
  int task_count() const { return static_cast<int>(range_begin_.size()) - 1; }
  int level_count() const { return static_cast<int>(level_begin_.size()) - 1; }
  // The speed-up of one solve on `threads` threads that the schedule allows in the work
  // model (each level takes its largest task or its work / threads, whichever is more).
  double schedule_speedup(int threads) const;
  const std::vector<int>& old_to_new() const { return old_to_new_; }
  // The parallelism the elimination tree allows: total work and the span (the heaviest
  // root-to-leaf path, which no schedule can beat), for one factorisation and one solve
  // pair, in the flop model above. work / span bounds the speed-up on any thread count.
  struct TreeParallelism {
    double factor_work = 0.0, factor_span = 0.0, solve_work = 0.0, solve_span = 0.0;
  };
  TreeParallelism tree_parallelism() const;

 private:
  struct Scratch {
    std::vector<double> y;
    std::vector<int> flag, pattern;
    // The supernodal factorisation's: the supernode's dense front, a descendant's update,
    // the pivots of the front and each row's place in the front (local).
    std::vector<double> front, update, panel, pivots;
    std::vector<int> local;
  };
  static constexpr int kMaxRunners = 256;
  void factor_rows(int begin, int end, Scratch& s, bool positive_definite, bool& ok);
  void plan_supernodes();
  void factor_supernode(int s, Scratch& scratch, bool positive_definite, bool& ok);
  void plan(int parts);
  void plan_accumulators();
  void share_row_indices();
  void size_scratch();
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
  std::vector<double> row_factor_work_;  // per row: its share of factor_flops_
  std::vector<double> lx_, d_;
  std::vector<float> lx_float_;  // see keep_float_copy
  // The plan: task t owns the column ranges ranges_[range_begin_[t] .. range_begin_[t+1])
  // (each [first, last+1)); the tasks of level l are level_begin_[l] .. level_begin_[l+1].
  // split_[j] is the first entry of column j that lies in a row of another task.
  std::vector<int> range_begin_, level_begin_, task_of_;
  std::vector<std::pair<int, int>> ranges_;
  std::vector<double> task_work_;
  std::vector<int> split_;
  // The forward solve's accumulators: task t's slots are acc_[acc_begin_[t] ..]; the rows
  // from split_ on of the supernode ending at column j go to ext_slots_[ext_base_[j] ..];
  // row j adds acc_[gather_slots_[gather_begin_[j] ..]] before its task starts.
  std::vector<int> acc_begin_, ext_base_, ext_slots_, gather_begin_, gather_slots_;
  std::vector<double> acc_;
  std::vector<Scratch> scratch_;  // one per thread (factorize)
  FactorMethod factor_method_ = FactorMethod::kSupernodal;
  // The supernodal factorisation's plan (plan_supernodes): supernode s is the columns
  // sn_first_[s] .. sn_first_[s + 1] - 1; sn_of_[j] is column j's. Its rows below (m of
  // them) times its columns are kept dense, column-major, at ls_[ls_begin_[s] ..] for the
  // supernodes above. The descendants d that update s, in ascending order, are
  // upd_d_[upd_begin_[s] ..], each with its rows in s: entries upd_p1_ .. upd_p2_ of d's
  // rows below. A's entries of s's columns go from ax_[asm_src_[q]] to its front at
  // asm_dst_[q], q in asm_begin_[s] ...
  std::vector<int> sn_first_, sn_of_, ls_begin_, upd_begin_, upd_d_, upd_p1_, upd_p2_;
  std::vector<int> asm_begin_, asm_src_, asm_dst_;
  std::vector<double> ls_;
  std::size_t front_size_ = 0, update_size_ = 0, panel_size_ = 0;
  int front_width_ = 0;
  // The solves' row indices: column j's are solve_rows_[solve_row_begin_[j] ..], one list
  // per supernode (share_row_indices).
  std::vector<int> solve_rows_, solve_row_begin_;
  std::vector<int> snode_first_, snode_last_;  // per column: its supernode's first and last
  // Each task's scratch for its dense supernodes (solve_with): dense_scratch_[dense_begin_[t] ..].
  std::vector<int> dense_begin_;
  std::vector<double> dense_scratch_;
  VecX work_;
  double factor_flops_ = 0.0, solve_flops_ = 0.0, serial_fraction_ = 0.0;
};

}  // namespace invfree
