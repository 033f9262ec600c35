// Vector kernels of the Newton and CG loops (dot products, norms, updates, the symmetric
// sparse product) split over the thread pool in fixed blocks. Inputs: vectors of one length
// n (and, for the product, H in full symmetric CSC storage plus its couplings). Reductions
// add the blocks' partial results in block order and the blocks depend on n alone, so every
// result is bit-identical for 1, 2 or N threads (parallel.h). Within a block Eigen's own
// vectorised kernels run. At n_seg 256 a CG iteration makes six passes over 132 k unknowns;
// done on the caller's thread alone they were a fifth of its serial time.
#pragma once

#include <Eigen/SparseCore>
#include <algorithm>
#include <span>

#include "linalg/node_coupling.h"
#include "linalg/parallel.h"
#include "types.h"

namespace invfree {

// Blocks of at least 8,192 entries (smaller vectors run in one block, inline), at most 256.
inline BlockSplit vector_blocks(Eigen::Index n) {
  return split_blocks(static_cast<int>(n), 8192, 256);
}

// fn(begin, length, block) for every block; fn writes only its block's entries.
template <class Fn>
void for_each_block(Eigen::Index n, Fn&& fn) {
  const BlockSplit blocks = vector_blocks(n);
  const int size = static_cast<int>(n);
  thread_pool().run(blocks.blocks, [&](int b) {
    const int begin = blocks.begin(b);
    fn(begin, blocks.end(b, size) - begin, b);
  });
}

// The sum over blocks of fn(begin, length), added in block order.
template <class Fn>
double sum_over_blocks(Eigen::Index n, Fn&& fn) {
  double partial[256];
  for_each_block(n, [&](int begin, int length, int b) { partial[b] = fn(begin, length); });
  double sum = 0.0;
  for (int b = 0, blocks = vector_blocks(n).blocks; b < blocks; ++b) sum += partial[b];
  return sum;
}

inline double blocked_dot(const VecX& a, const VecX& b) {
  return sum_over_blocks(a.size(), [&](int begin, int length) {
    return a.segment(begin, length).dot(b.segment(begin, length));
  });
}

inline void blocked_copy(const VecX& in, VecX& out) {
  out.resize(in.size());
  for_each_block(in.size(), [&](int begin, int length, int) {
    out.segment(begin, length) = in.segment(begin, length);
  });
}

// out = a + alpha b, elementwise (each entry as Eigen's own expression computes it).
inline void blocked_add_scaled(const VecX& a, double alpha, const VecX& b, VecX& out) {
  out.resize(a.size());
  for_each_block(a.size(), [&](int begin, int length, int) {
    out.segment(begin, length) = a.segment(begin, length) + alpha * b.segment(begin, length);
  });
}

inline void blocked_negate(const VecX& in, VecX& out) {
  out.resize(in.size());
  for_each_block(in.size(), [&](int begin, int length, int) {
    out.segment(begin, length) = -in.segment(begin, length);
  });
}

// max |v_i| (a maximum: the same whatever the blocks).
inline double blocked_max_abs(const VecX& v) {
  double partial[256];
  for_each_block(v.size(), [&](int begin, int length, int b) {
    partial[b] = v.segment(begin, length).lpNorm<Eigen::Infinity>();
  });
  double m = 0.0;
  for (int b = 0, blocks = vector_blocks(v.size()).blocks; b < blocks; ++b)
    m = std::max(m, partial[b]);
  return m;
}

// y = H v, H = h (full symmetric storage: column i is row i) plus the couplings outside its
// pattern; returns v.y. Rows in fixed blocks, then the couplings in list order.
double multiply_symmetric(const Eigen::SparseMatrix<double>& h,
                          std::span<const NodeCoupling> couplings, const VecX& v, VecX& y);

}  // namespace invfree
