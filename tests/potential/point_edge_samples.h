// Point-edge configurations for the self-contact tests: a generic sweep, points whose
// projection falls just before, on and just past either end of the edge (the regime
// switches), points very close to the edge's line, short edges and far points; plus a
// central-difference Jacobian for Hessian checks.
#pragma once

#include <functional>
#include <random>
#include <vector>

#include "types.h"

namespace invfree::test {

struct PointEdgeSample {
  Vec2 p, a, b;
};

// Points at parameter r along the edge (r < 0 or r > 1: beyond an end) and signed offset h
// along its normal, for a random edge of random length `length` (scale) and direction.
inline PointEdgeSample point_edge_at(std::mt19937& rng, double length, double r, double h) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), angle(-3.14159, 3.14159);
  const double t = angle(rng);
  const Vec2 dir(std::cos(t), std::sin(t)), normal(-dir.y(), dir.x());
  const Vec2 a(u(rng), u(rng));
  const Vec2 b = a + length * dir;
  return {a + r * length * dir + h * length * normal, a, b};
}

inline std::vector<PointEdgeSample> point_edge_samples(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  std::vector<PointEdgeSample> out;
  for (int k = 0; k < count; ++k) {
    const double side = u(rng) > 0 ? 1.0 : -1.0;
    const double len = std::pow(10.0, -2.0 * unit(rng));  // 0.01 .. 1
    switch (k % 6) {
      case 0:  // generic
        out.push_back({Vec2(u(rng), u(rng)), Vec2(u(rng), u(rng)), Vec2(u(rng), u(rng))});
        break;
      case 1:  // interior, near the line
        out.push_back(point_edge_at(rng, len, 0.05 + 0.9 * unit(rng), side * 1e-3 * unit(rng)));
        break;
      case 2: {  // just either side of an end: the switch
        const double delta = (u(rng) > 0 ? 1e-3 : 1e-5) * (u(rng) > 0 ? 1.0 : -1.0);
        const double end = u(rng) > 0 ? 0.0 : 1.0;
        out.push_back(point_edge_at(rng, len, end + delta, side * (0.05 + unit(rng))));
        break;
      }
      case 3:  // beyond an end, point-point
        out.push_back(point_edge_at(
            rng, len, u(rng) > 0 ? -0.5 * unit(rng) - 1e-3 : 1.0 + 0.5 * unit(rng) + 1e-3,
            side * unit(rng)));
        break;
      case 4:  // short edge, far point
        out.push_back(point_edge_at(rng, 1e-4, 0.5 + 100.0 * u(rng), side * 300.0 * unit(rng)));
        break;
      default:  // long edge, point close
        out.push_back(point_edge_at(rng, 1.0, unit(rng), side * (1e-4 + 1e-3 * unit(rng))));
        break;
    }
  }
  return out;
}

inline Vec6 stack(const PointEdgeSample& s) {
  Vec6 x;
  x << s.p, s.a, s.b;
  return x;
}

// Central-difference Jacobian of a 6 -> 6 map.
inline Mat6 fd_jacobian(const std::function<Vec6(const Vec6&)>& f, const Vec6& x, double eps) {
  Mat6 j;
  for (int k = 0; k < 6; ++k) {
    Vec6 a = x, b = x;
    a[k] += eps;
    b[k] -= eps;
    j.col(k) = (f(a) - f(b)) / (2.0 * eps);
  }
  return j;
}

}  // namespace invfree::test
