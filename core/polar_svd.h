// Closed-form polar SVD of a 2x2 matrix (the lecture's Algorithm 6 without an
// iterative SVD): F = U diag(sigma) V^T with U, V proper rotations (det = +1) and
// sigma(0) >= |sigma(1)|; sigma(1) < 0 exactly when det F < 0.
//
// Derivation: split F into a similarity part e*I + h*J (J = 90 degree rotation) and a
// reflection part f*K + g*L (K = diag(1,-1), L = [0 1; 1 0]). With q = |(e,h)|,
// r = |(f,g)|, a1 = atan2(g, f), a2 = atan2(h, e):
//   F = R((a2 + a1)/2) diag(q + r, q - r) R((a2 - a1)/2)
// (see e.g. J. Blinn, "Consider the lowly 2x2 matrix", 1996).
// sigma(1) is recomputed as det(F)/sigma(0) so that a small singular value keeps its
// relative accuracy instead of suffering the cancellation in q - r.
#pragma once

#include <cmath>

#include "core/types.h"

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
  const double q = std::hypot(e, h);
  const double r = std::hypot(f, g);
  const double a1 = std::atan2(g, f);
  const double a2 = std::atan2(h, e);
  PolarSvd out;
  out.U = rotation(0.5 * (a2 + a1));
  out.V = rotation(0.5 * (a2 - a1)).transpose();
  const double s0 = q + r;
  out.sigma(0) = s0;
  out.sigma(1) = s0 > 0.0 ? determinant(F) / s0 : 0.0;
  return out;
}

}  // namespace invfree
