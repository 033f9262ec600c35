// The per-triangle chain rule of lecture 9: F = [x2-x1, x3-x1] IB with
// IB = [X2-X1, X3-X1]^-1, the constant Jacobian d vec(F) / d [x1; x2; x3] (4x6, rows in
// the column-major order [F11, F21, F12, F22]), and from it
//   gradient = area * dF/dx^T vec(P),   Hessian = area * dF/dx^T dP/dF dF/dx.
#pragma once

#include "core/material.h"
#include "core/psd_projection.h"
#include "core/types.h"

namespace invfree {

inline Mat2 deformation_gradient(const Vec2& x1, const Vec2& x2, const Vec2& x3, const Mat2& IB) {
  Mat2 ds;
  ds.col(0) = x2 - x1;
  ds.col(1) = x3 - x1;
  return ds * IB;
}

inline Mat46 deformation_gradient_jacobian(const Mat2& IB) {
  // F_ij = (x2 - x1)_i IB_0j + (x3 - x1)_i IB_1j; row of F_ij is i + 2j, column of node
  // a's component i is 2a + i.
  Mat46 d = Mat46::Zero();
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int row = i + 2 * j;
      d(row, i) = -IB(0, j) - IB(1, j);
      d(row, 2 + i) = IB(0, j);
      d(row, 4 + i) = IB(1, j);
    }
  return d;
}

// Elastic energy, gradient and Hessian of one triangle for a model type M.
template <class M>
struct TriangleElasticity {
  static Vec6 gradient(const Mat2& F, const Mat46& dFdx, double area, const Lame& l) {
    return area * dFdx.transpose() * flatten(M::first_piola(F, l));
  }
  static Mat6 hessian(const Mat2& F, const Mat46& dFdx, double area, const Lame& l,
                      HessianProjection projection) {
    const Mat4 dPdF = M::stress_derivative(F, l, projection == HessianProjection::Diagonal);
    Mat6 h = area * dFdx.transpose() * dPdF * dFdx;
    if (projection == HessianProjection::Full) h = project_psd<6>(h);
    return h;
  }
};

}  // namespace invfree
