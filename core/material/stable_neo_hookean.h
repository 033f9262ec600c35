// Stable neo-Hookean (Smith, de Goes, Kim 2018, "Stable Neo-Hookean Flesh Simulation",
// the form without the log(I_C + 1) regulariser, as in Kim & Eberle's "Dynamic
// Deformables" course notes), in 2D:
//   Psi(F) = mu/2 (|F|^2 - 2) - mu (J - 1) + lam/2 (J - 1)^2,   lam = lambda + mu
// The shift lam = lambda + mu (the paper's Sec. 3.4 reparametrisation for this form)
// makes it consistent with linear elasticity at F = I (d2Psi/ds_i ds_j = 2 mu d_ij + lambda).
// Defined for every F, including det F <= 0: an invertible model.
// With c = lam (J - 1) - mu:  P = mu F + c cof(F),
//   Psi_1 = mu s1 + c s2,  A = [[mu + lam s2^2, lam (2J - 1) - mu], [., mu + lam s1^2]],
//   flip = mu - c,  twist = mu + c.
#pragma once

#include "material/diagonal_space.h"
#include "material/material.h"

namespace invfree {

struct StableNeoHookean {
  static double energy_density(const Mat2& F, const Lame& m) {
    const double lam = m.lambda + m.mu;
    const double J = F.determinant();
    return 0.5 * m.mu * (F.squaredNorm() - 2.0) - m.mu * (J - 1.0) +
           0.5 * lam * (J - 1.0) * (J - 1.0);
  }

  static Mat2 first_piola(const Mat2& F, const Lame& m) {
    const double lam = m.lambda + m.mu;
    Mat2 cof;
    cof << F(1, 1), -F(1, 0), -F(0, 1), F(0, 0);
    return m.mu * F + (lam * (F.determinant() - 1.0) - m.mu) * cof;
  }

  static Vec2 diagonal_stress(const Vec2& s, const Lame& m) {
    const double c = (m.lambda + m.mu) * (s(0) * s(1) - 1.0) - m.mu;
    return {m.mu * s(0) + c * s(1), m.mu * s(1) + c * s(0)};
  }

  static DiagonalHessian diagonal_hessian(const Vec2& s, const Lame& m) {
    const double lam = m.lambda + m.mu;
    const double J = s(0) * s(1);
    const double c = lam * (J - 1.0) - m.mu;
    DiagonalHessian d;
    d.A(0, 0) = m.mu + lam * s(1) * s(1);
    d.A(1, 1) = m.mu + lam * s(0) * s(0);
    d.A(0, 1) = d.A(1, 0) = lam * (2.0 * J - 1.0) - m.mu;
    d.flip = m.mu - c;
    d.twist = m.mu + c;
    return d;
  }

  static Mat4 stress_derivative(const Mat2& F, const Lame& m, bool project_to_psd) {
    const PolarSvd svd = polar_svd(F);
    return compose_stress_derivative(svd, diagonal_hessian(svd.sigma, m), project_to_psd);
  }
};

}  // namespace invfree
