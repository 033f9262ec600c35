// Unsigned distance from a point p to a segment (edge) a-b in the plane, SQUARED, with its
// gradient and Hessian over the six coordinates (p, a, b) in that order.
// The closest point is an end of the edge or lies inside it, so the distance has three
// regimes, each a smooth expression of its own (the regime is chosen first, then the
// expression of that regime is differentiated, as in the solid-sim-tutorial's
// PointEdgeDistance and ipc-toolkit's point_edge distance):
//   FirstEnd   (projection before a):  D = |p - a|^2
//   SecondEnd  (projection beyond b):  D = |p - b|^2
//   Interior   (projection inside):    D = c^2 / l,  c = (b - a) x (p - a),  l = |b - a|^2
// D is C1 across the switches (the Hessian jumps there). Squared, not unsquared: D is a
// polynomial (point-point) or a ratio of polynomials (point-line), so no square root and no
// 1/d terms in the derivatives; the tutorial's self-contact barrier is written on D, and
// the barrier built on it (self_contact_barrier.h) keeps the ground's b and kappa scaling.
// A zero-length edge counts as FirstEnd (the point-point distance to it).
#pragma once

#include "types.h"

namespace invfree {

enum class PointEdgeRegime { FirstEnd, SecondEnd, Interior };

inline PointEdgeRegime point_edge_regime(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 e = b - a;
  const double t = e.dot(p - a);
  const double l = e.squaredNorm();
  if (t < 0.0 || l == 0.0) return PointEdgeRegime::FirstEnd;
  if (t > l) return PointEdgeRegime::SecondEnd;
  return PointEdgeRegime::Interior;
}

// The closest point of the edge, a + r (b - a): r = 0, 1 or the projection's parameter.
inline double point_edge_closest_parameter(const Vec2& p, const Vec2& a, const Vec2& b,
                                           PointEdgeRegime regime) {
  switch (regime) {
    case PointEdgeRegime::FirstEnd:
      return 0.0;
    case PointEdgeRegime::SecondEnd:
      return 1.0;
    default:
      return (b - a).dot(p - a) / (b - a).squaredNorm();
  }
}

inline double point_edge_distance_squared(const Vec2& p, const Vec2& a, const Vec2& b,
                                          PointEdgeRegime regime) {
  switch (regime) {
    case PointEdgeRegime::FirstEnd:
      return (p - a).squaredNorm();
    case PointEdgeRegime::SecondEnd:
      return (p - b).squaredNorm();
    default: {
      const Vec2 e = b - a, u = p - a;
      const double c = e.x() * u.y() - e.y() * u.x();
      return c * c / e.squaredNorm();
    }
  }
}

inline double point_edge_distance_squared(const Vec2& p, const Vec2& a, const Vec2& b) {
  return point_edge_distance_squared(p, a, b, point_edge_regime(p, a, b));
}

namespace point_edge_detail {

// Point-line pieces: c = (b - a) x (p - a) and l = |b - a|^2 with their gradients over
// (p, a, b); c and l are quadratic, with constant Hessians.
struct LineTerms {
  double c, l;
  Vec6 dc, dl;
};

inline LineTerms line_terms(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 e = b - a, u = p - a;
  LineTerms t;
  t.c = e.x() * u.y() - e.y() * u.x();
  t.l = e.squaredNorm();
  const Vec2 dc_p(-e.y(), e.x()), dc_b(u.y(), -u.x());
  t.dc << dc_p, -dc_p - dc_b, dc_b;
  t.dl << Vec2::Zero(), -2.0 * e, 2.0 * e;
  return t;
}

// Hessians of c and l: c = u^T R e with u = p - a, e = b - a, R the 90-degree rotation.
inline Mat6 cross_hessian() {
  Eigen::Matrix<double, 2, 6> du, de;
  du << Mat2::Identity(), -Mat2::Identity(), Mat2::Zero();
  de << Mat2::Zero(), -Mat2::Identity(), Mat2::Identity();
  Mat2 r;
  r << 0.0, -1.0, 1.0, 0.0;
  return du.transpose() * r * de + de.transpose() * r.transpose() * du;
}

inline Mat6 length_hessian() {
  Eigen::Matrix<double, 2, 6> de;
  de << Mat2::Zero(), -Mat2::Identity(), Mat2::Identity();
  return 2.0 * de.transpose() * de;
}

// Offsets of the two points of a point-point regime among the six coordinates.
inline int end_offset(PointEdgeRegime regime) {
  return regime == PointEdgeRegime::FirstEnd ? 2 : 4;
}

}  // namespace point_edge_detail

inline Vec6 point_edge_distance_squared_gradient(const Vec2& p, const Vec2& a, const Vec2& b,
                                                 PointEdgeRegime regime) {
  using namespace point_edge_detail;
  Vec6 g = Vec6::Zero();
  if (regime == PointEdgeRegime::Interior) {
    const LineTerms t = line_terms(p, a, b);
    return (2.0 * t.c / t.l) * t.dc - (t.c * t.c / (t.l * t.l)) * t.dl;
  }
  const int q = end_offset(regime);
  const Vec2 d = 2.0 * (p - (regime == PointEdgeRegime::FirstEnd ? a : b));
  g.segment<2>(0) = d;
  g.segment<2>(q) = -d;
  return g;
}

inline Mat6 point_edge_distance_squared_hessian(const Vec2& p, const Vec2& a, const Vec2& b,
                                                PointEdgeRegime regime) {
  using namespace point_edge_detail;
  Mat6 h = Mat6::Zero();
  if (regime == PointEdgeRegime::Interior) {
    const LineTerms t = line_terms(p, a, b);
    const double c = t.c, l = t.l, c2 = c * c;
    h = (2.0 / l) * t.dc * t.dc.transpose() + (2.0 * c / l) * cross_hessian() -
        (2.0 * c / (l * l)) * (t.dc * t.dl.transpose() + t.dl * t.dc.transpose()) +
        (2.0 * c2 / (l * l * l)) * t.dl * t.dl.transpose() - (c2 / (l * l)) * length_hessian();
    return h;
  }
  const int q = end_offset(regime);
  h.block<2, 2>(0, 0) = h.block<2, 2>(q, q) = 2.0 * Mat2::Identity();
  h.block<2, 2>(0, q) = h.block<2, 2>(q, 0) = -2.0 * Mat2::Identity();
  return h;
}

}  // namespace invfree
