// Fixed-size Eigen aliases shared by the whole core. 2D only: the project models
// planar triangles, so every small matrix here has a compile-time size.
#pragma once

#include <Eigen/Dense>
#include <cmath>

namespace invfree {

using Vec2 = Eigen::Vector2d;
using Vec4 = Eigen::Vector4d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat2 = Eigen::Matrix2d;
using Mat4 = Eigen::Matrix4d;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat46 = Eigen::Matrix<double, 4, 6>;
using VecX = Eigen::VectorXd;

// Column-major flattening of a 2x2 matrix: [F11, F21, F12, F22]. Every 4-vector and
// 4x4 "dP/dF" in the project uses this order (Eigen's own storage order).
inline Vec4 flatten(const Mat2& m) {
  return Eigen::Map<const Vec4>(m.data());
}
inline Mat2 unflatten(const Vec4& v) {
  return Eigen::Map<const Mat2>(v.data());
}

// det(F) = F11 F22 - F12 F21 with Kahan's fused-multiply-add trick: nearly correctly
// rounded even when the two products cancel (a thin triangle, a small singular value).
inline double determinant(const Mat2& f) {
  const double w = f(0, 1) * f(1, 0);
  const double e = std::fma(-f(0, 1), f(1, 0), w);
  return std::fma(f(0, 0), f(1, 1), -w) + e;
}

}  // namespace invfree
