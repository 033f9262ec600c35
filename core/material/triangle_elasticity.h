// The per-triangle chain rule of lecture 9: F = [x2-x1, x3-x1] IB with
// IB = [X2-X1, X3-X1]^-1, the constant Jacobian d vec(F) / d [x1; x2; x3] (4x6, rows in
// the column-major order [F11, F21, F12, F22]), and from it
//   gradient = area * dF/dx^T vec(P),   Hessian = area * dF/dx^T dP/dF dF/dx.
// The assembly's hot path, `gradient_hessian`, does the same without forming the 4x6
// Jacobian: dF_ij/dx_ak = delta_ik D_aj with D = [-(IB_0 + IB_1); IB_0; IB_1] (rows of IB),
// so the products cost a third of the dense ones, P and dP/dF share J and ln J, and the
// Hessian is built on its upper triangle and mirrored (exactly symmetric, as CG wants).
#pragma once

#include <type_traits>

#include "material/material.h"
#include "material/psd_projection.h"
#include "types.h"

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

// P and dP/dF at once: the model's fused version when it has one (sharing work between
// the two), otherwise the two separate functions.
template <class M>
inline void stress_and_derivative(const Mat2& F, const Lame& l, bool project_to_psd, Mat2& P,
                                  Mat4& dPdF) {
  if constexpr (requires { M::stress_and_derivative(F, l, project_to_psd, P, dPdF); }) {
    M::stress_and_derivative(F, l, project_to_psd, P, dPdF);
  } else {
    P = M::first_piola(F, l);
    dPdF = M::stress_derivative(F, l, project_to_psd);
  }
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
  // Gradient and Hessian of area * Psi(F) at once, from IB = [X2-X1, X3-X1]^-1.
  static void gradient_hessian(const Mat2& F, const Mat2& IB, double area, const Lame& l,
                               HessianProjection projection, Vec6& g, Mat6& H) {
    Mat2 P;
    Mat4 C;
    stress_and_derivative<M>(F, l, projection == HessianProjection::Diagonal, P, C);
    const double D[3][2] = {
        {-IB(0, 0) - IB(1, 0), -IB(0, 1) - IB(1, 1)}, {IB(0, 0), IB(0, 1)}, {IB(1, 0), IB(1, 1)}};
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 2; ++i) g(2 * a + i) = area * (P(i, 0) * D[a][0] + P(i, 1) * D[a][1]);
    // T = dPdF * dF/dx (4x6), column 2b+k = D_b0 C(:, k) + D_b1 C(:, k+2).
    Eigen::Matrix<double, 4, 6> T;
    for (int b = 0; b < 3; ++b)
      for (int k = 0; k < 2; ++k) T.col(2 * b + k) = D[b][0] * C.col(k) + D[b][1] * C.col(k + 2);
    // H(2a+i, 2b+k) = area (D_a0 T(i, 2b+k) + D_a1 T(i+2, 2b+k)), upper triangle, mirrored.
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 2; ++i) {
        const int row = 2 * a + i;
        for (int col = row; col < 6; ++col) {
          const double v = area * (D[a][0] * T(i, col) + D[a][1] * T(i + 2, col));
          H(row, col) = v;
          H(col, row) = v;
        }
      }
    if (projection == HessianProjection::Full) {
      H = project_psd<6>(H);
      H = (0.5 * (H + H.transpose()))
              .eval();  // the eigen-reconstruction is symmetric only to rounding
    }
  }
};

}  // namespace invfree
