// Linear elasticity (lecture 9, "Simplified Models"):
//   Psi(F) = mu |eps|^2 + lambda/2 tr^2(eps),  eps = (F + F^T)/2 - I,
//   P = 2 mu eps + lambda tr(eps) I,
//   dP_ij/dF_kl = mu (d_ik d_jl + d_il d_jk) + lambda d_ij d_kl   (constant, PSD).
// Not rotation invariant (it is the small-strain model), invertible, needs no SVD.
#pragma once

#include "material/material.h"
#include "types.h"

namespace invfree {

struct LinearElasticity {
  static Mat2 strain(const Mat2& F) { return 0.5 * (F + F.transpose()) - Mat2::Identity(); }

  static double energy_density(const Mat2& F, const Lame& m) {
    const Mat2 e = strain(F);
    const double tr = e.trace();
    return m.mu * e.squaredNorm() + 0.5 * m.lambda * tr * tr;
  }

  static Mat2 first_piola(const Mat2& F, const Lame& m) {
    const Mat2 e = strain(F);
    return 2.0 * m.mu * e + m.lambda * e.trace() * Mat2::Identity();
  }

  static Mat4 stress_derivative(const Mat2& /*F*/, const Lame& m, bool /*project_to_psd*/) {
    // Flattened order [F11, F21, F12, F22].
    Mat4 d = Mat4::Zero();
    d(0, 0) = d(3, 3) = 2.0 * m.mu + m.lambda;
    d(0, 3) = d(3, 0) = m.lambda;
    d(1, 1) = d(2, 2) = d(1, 2) = d(2, 1) = m.mu;
    return d;
  }
};

}  // namespace invfree
