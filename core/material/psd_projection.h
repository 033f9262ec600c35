// Projection of symmetric matrices onto the positive semi-definite cone by clamping
// negative eigenvalues to zero. Inputs: a symmetric matrix. Output: the nearest PSD
// matrix in the Frobenius norm. The 2x2 case is closed form (it runs per triangle in
// the lecture's diagonal-space projection); the 6x6 case uses Eigen's self-adjoint
// solver (the "whole element Hessian" alternative compared in `invfree study`).
#pragma once

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "types.h"

namespace invfree {

inline Mat2 project_psd(const Mat2& a) {
  const double mean = 0.5 * (a(0, 0) + a(1, 1));
  const double half_diff = 0.5 * (a(0, 0) - a(1, 1));
  const double radius = std::hypot(half_diff, a(0, 1));
  const double l0 = mean + radius, l1 = mean - radius;
  if (l1 >= 0.0) return a;
  if (l0 <= 0.0) return Mat2::Zero();
  // Only l0 survives: a = l0 * v v^T with v the eigenvector of l0.
  Vec2 v;
  if (half_diff >= 0.0)
    v << radius + half_diff, a(0, 1);
  else
    v << a(0, 1), radius - half_diff;
  const double n2 = v.squaredNorm();
  if (n2 == 0.0) return Mat2::Identity() * std::max(l0, 0.0);
  return (l0 / n2) * v * v.transpose();
}

template <int N>
Eigen::Matrix<double, N, N> project_psd(const Eigen::Matrix<double, N, N>& a) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(a);
  const auto& values = eig.eigenvalues();
  if (values.minCoeff() >= 0.0) return a;
  return eig.eigenvectors() * values.cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace invfree
