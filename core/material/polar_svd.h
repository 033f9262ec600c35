// Closed-form polar SVD of a 2x2 matrix (the lecture's Algorithm 6 without an
// iterative SVD): F = U diag(sigma) V^T with U, V proper rotations (det = +1) and
// sigma(0) >= |sigma(1)|; sigma(1) < 0 exactly when det F < 0.
//
// Derivation: split F into a similarity part e*I + h*J (J = 90 degree rotation) and a
// reflection part f*K + g*L (K = diag(1,-1), L = [0 1; 1 0]). With q = |(e,h)|,
// r = |(f,g)|, a1 = atan2(g, f), a2 = atan2(h, e):
//   F = R((a2 + a1)/2) diag(q + r, q - r) R((a2 - a1)/2)
// (see e.g. J. Blinn, "Consider the lowly 2x2 matrix", 1996).
// No trigonometric function is evaluated: cos/sin of a1 and a2 are (f, g)/r and (e, h)/q,
// the angle a1 + a2 follows by the addition formulas, its half by the half-angle formula
// (the branch that divides by the larger of cos and sin), and the second angle is the
// first minus a1. Either half angle works: it negates U and V together, leaving F
// unchanged. This is the per-triangle hot path of every Hessian, so it matters.
// sigma(1) is recomputed as det(F)/sigma(0) so that a small singular value keeps its
// relative accuracy instead of suffering the cancellation in q - r.
#pragma once

#include <cmath>

#include "types.h"

namespace invfree {

struct PolarSvd {
  Mat2 U;
  Vec2 sigma;
  Mat2 V;
};

inline Mat2 rotation(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Mat2 r;
  r << c, -s, s, c;
  return r;
}

inline PolarSvd polar_svd(const Mat2& F) {
  const double e = 0.5 * (F(0, 0) + F(1, 1));
  const double f = 0.5 * (F(0, 0) - F(1, 1));
  const double g = 0.5 * (F(1, 0) + F(0, 1));
  const double h = 0.5 * (F(1, 0) - F(0, 1));
  const double q = std::sqrt(e * e + h * h);
  const double r = std::sqrt(f * f + g * g);
  // (cos, sin) of a1 and a2; a zero vector has angle 0, as atan2(0, 0).
  const double c1 = r > 0.0 ? f / r : 1.0, s1 = r > 0.0 ? g / r : 0.0;
  const double c2 = q > 0.0 ? e / q : 1.0, s2 = q > 0.0 ? h / q : 0.0;
  // (cos, sin) of a1 + a2, then of half of it: the angle of U.
  const double cp = c2 * c1 - s2 * s1, sp = s2 * c1 + c2 * s1;
  double cu, su;
  if (cp >= 0.0) {
    cu = std::sqrt(0.5 * (1.0 + cp));
    su = sp / (2.0 * cu);
  } else {
    su = std::sqrt(0.5 * (1.0 - cp));
    cu = sp / (2.0 * su);
  }
  // The angle of V^T is the angle of U minus a1.
  const double cv = cu * c1 + su * s1, sv = su * c1 - cu * s1;
  PolarSvd out;
  out.U << cu, -su, su, cu;
  out.V << cv, sv, -sv, cv;  // V = R(angle)^T
  const double s0 = q + r;
  out.sigma(0) = s0;
  out.sigma(1) = s0 > 0.0 ? determinant(F) / s0 : 0.0;
  return out;
}

}  // namespace invfree
