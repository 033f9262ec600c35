// As-rigid-as-possible (lecture 9, "Simplified Models"):
//   Psi(F) = mu sum_i (s_i - 1)^2 = mu (|F|^2 - 2 tr(S) + 2),  F = R S (polar),
// with signed singular values, so it is defined for inverted F too (invertible model).
// In 2D tr(S) = s1 + s2 = 2 q where q = |(F11 + F22, F21 - F12)| / 2, and R is the
// rotation by atan2(F21 - F12, F11 + F22): P = 2 mu (F - R) without an SVD.
// Diagonal space: Psi_i = 2 mu (s_i - 1), A = 2 mu I, flip = 2 mu,
//   twist = 2 mu (s1 + s2 - 2)/(s1 + s2)  -- genuinely singular at s1 + s2 = 0, where the
// polar rotation is undefined; there it is evaluated at s1 + s2 = 1e-12 (and projection
// clamps it to zero anyway).
#pragma once

#include <algorithm>
#include <cmath>

#include "material/diagonal_space.h"
#include "material/material.h"

namespace invfree {

struct Arap {
  static double trace_of_stretch(const Mat2& F) {
    return std::hypot(F(0, 0) + F(1, 1), F(1, 0) - F(0, 1));
  }

  static double energy_density(const Mat2& F, const Lame& m) {
    return m.mu * (F.squaredNorm() - 2.0 * trace_of_stretch(F) + 2.0);
  }

  static Mat2 first_piola(const Mat2& F, const Lame& m) {
    const double angle = std::atan2(F(1, 0) - F(0, 1), F(0, 0) + F(1, 1));
    return 2.0 * m.mu * (F - rotation(angle));
  }

  static Vec2 diagonal_stress(const Vec2& s, const Lame& m) {
    return {2.0 * m.mu * (s(0) - 1.0), 2.0 * m.mu * (s(1) - 1.0)};
  }

  static DiagonalHessian diagonal_hessian(const Vec2& s, const Lame& m) {
    const double sum = std::max(s(0) + s(1), 1e-12);
    DiagonalHessian d;
    d.A = 2.0 * m.mu * Mat2::Identity();
    d.flip = 2.0 * m.mu;
    d.twist = 2.0 * m.mu * (sum - 2.0) / sum;
    return d;
  }

  static Mat4 stress_derivative(const Mat2& F, const Lame& m, bool project_to_psd) {
    const PolarSvd svd = polar_svd(F);
    return compose_stress_derivative(svd, diagonal_hessian(svd.sigma, m), project_to_psd);
  }
};

}  // namespace invfree
