// Test matrices on the Newton system's sparsity pattern, shared by the factorisation tests.
#pragma once

#include <Eigen/SparseCore>
#include <cmath>
#include <random>

#include "linalg/sparse_hessian.h"
#include "scene/mesh.h"

namespace invfree {

// A matrix on the Newton system's pattern (mesh pairs plus the dense ceiling row) with
// random symmetric off-diagonal values and diagonal `shift` + the row's absolute sum: SPD
// for shift > 0; shift < 0 makes some diagonal entries negative (indefinite).
inline Eigen::SparseMatrix<double> mesh_matrix(int n_seg, double shift, unsigned seed) {
  const SparseHessian hess = build_sparse_hessian(square_mesh(1.0, n_seg), true);
  Eigen::SparseMatrix<double> a = hess.matrix;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int col = 0; col < a.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it)
      if (it.row() < col) {
        const double v = u(rng);
        it.valueRef() = v;
        a.coeffRef(col, it.row()) = v;
      }
  for (int col = 0; col < a.outerSize(); ++col) {
    double sum = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it)
      if (it.row() != col) sum += std::abs(it.value());
    a.coeffRef(col, col) =
        sum + (shift < 0.0 && col % 7 == 3 ? shift - 2.0 * sum : std::abs(shift));
  }
  return a;
}

}  // namespace invfree
