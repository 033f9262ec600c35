// Neo-Hookean energy, exactly the lecture's:
//   Psi(F) = mu/2 (tr(F^T F) - 2) - mu ln J + lambda/2 ln^2 J,   J = det F > 0.
// Value and stress P = mu (F - F^-T) + lambda ln(J) F^-T need no SVD. The stress
// derivative is built in the diagonal space (lecture 9):
//   Psi_i      = mu (s_i - 1/s_i) + lambda ln(J) / s_i
//   Psi_ii     = mu (1 + 1/s_i^2) + lambda (1 - ln J) / s_i^2,  Psi_12 = lambda / J
//   flip  = (Psi_1 - Psi_2)/(s1 - s2) = mu + (mu - lambda ln J) / J
//   twist = (Psi_1 + Psi_2)/(s1 + s2) = mu + (lambda ln J - mu) / J
// (flip = 2 B_left and twist = 2 B_right of the lecture, simplified by hand so neither
// divides by s1 - s2 or s1 + s2). For J <= 0 the energy is +infinity: a barrier.
#pragma once

#include <cmath>
#include <limits>

#include "material/diagonal_space.h"
#include "material/material.h"

namespace invfree {

struct NeoHookean {
  static double energy_density(const Mat2& F, const Lame& m) {
    const double J = determinant(F);
    if (!(J > 0.0)) return std::numeric_limits<double>::infinity();
    const double lnJ = std::log(J);
    return 0.5 * m.mu * (F.squaredNorm() - 2.0) - m.mu * lnJ + 0.5 * m.lambda * lnJ * lnJ;
  }

  static Mat2 first_piola(const Mat2& F, const Lame& m) {
    const double J = determinant(F);
    Mat2 inv_t;  // F^-T = cof(F) / J
    inv_t << F(1, 1), -F(1, 0), -F(0, 1), F(0, 0);
    inv_t /= J;
    return m.mu * (F - inv_t) + m.lambda * std::log(J) * inv_t;
  }

  static Vec2 diagonal_stress(const Vec2& s, const Lame& m) {
    const double lnJ = std::log(s(0) * s(1));
    return {m.mu * (s(0) - 1.0 / s(0)) + m.lambda * lnJ / s(0),
            m.mu * (s(1) - 1.0 / s(1)) + m.lambda * lnJ / s(1)};
  }

  static DiagonalHessian diagonal_hessian(const Vec2& s, const Lame& m) {
    const double J = s(0) * s(1);
    return diagonal_hessian(s, J, std::log(J), m);
  }

  static DiagonalHessian diagonal_hessian(const Vec2& s, double J, double lnJ, const Lame& m) {
    const double inv0 = 1.0 / (s(0) * s(0)), inv1 = 1.0 / (s(1) * s(1));
    DiagonalHessian d;
    d.A(0, 0) = m.mu * (1.0 + inv0) + m.lambda * (1.0 - lnJ) * inv0;
    d.A(1, 1) = m.mu * (1.0 + inv1) + m.lambda * (1.0 - lnJ) * inv1;
    d.A(0, 1) = d.A(1, 0) = m.lambda / J;
    d.flip = m.mu + (m.mu - m.lambda * lnJ) / J;
    d.twist = m.mu + (m.lambda * lnJ - m.mu) / J;
    return d;
  }

  // P and dP/dF together: one determinant, one logarithm, one polar SVD.
  static void stress_and_derivative(const Mat2& F, const Lame& m, bool project_to_psd, Mat2& P,
                                    Mat4& dPdF) {
    const double J = determinant(F);
    const double lnJ = std::log(J);
    Mat2 inv_t;  // F^-T = cof(F) / J
    inv_t << F(1, 1), -F(1, 0), -F(0, 1), F(0, 0);
    inv_t /= J;
    P = m.mu * (F - inv_t) + m.lambda * lnJ * inv_t;
    const PolarSvd svd = polar_svd(F);
    dPdF = compose_stress_derivative(svd, diagonal_hessian(svd.sigma, J, lnJ, m), project_to_psd);
  }

  static Mat4 stress_derivative(const Mat2& F, const Lame& m, bool project_to_psd) {
    const PolarSvd svd = polar_svd(F);
    return compose_stress_derivative(svd, diagonal_hessian(svd.sigma, m), project_to_psd);
  }
};

}  // namespace invfree
