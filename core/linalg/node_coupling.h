// A 2x2 block of a symmetric matrix kept outside its sparse (CSC) pattern: the coupling of
// two nodes that share no triangle, from a contact that came after the pattern was made
// (SparseHessian::couplings). The matrix is then the CSC part plus a list of these, each
// orientation (i, j) and (j, i) listed; a node pair may be listed more than once (the
// blocks add). Only the PCG solve takes such a matrix (linear_solver.h, pcg.h).
#pragma once

#include <span>

#include "types.h"

namespace invfree {

struct NodeCoupling {
  int row_node = 0;  // rows 2 row_node, 2 row_node + 1
  int col_node = 0;  // columns 2 col_node, 2 col_node + 1
  Mat2 block = Mat2::Zero();
};

// y += C v over the couplings, in list order (serial: bit-identical for any thread
// count); returns v.(C v).
inline double add_couplings_product(std::span<const NodeCoupling> couplings, const VecX& v,
                                    VecX& y) {
  double dot = 0.0;
  for (const NodeCoupling& c : couplings) {
    const Vec2 cv = c.block * v.segment<2>(2 * c.col_node);
    y.segment<2>(2 * c.row_node) += cv;
    dot += v.segment<2>(2 * c.row_node).dot(cv);
  }
  return dot;
}

}  // namespace invfree
