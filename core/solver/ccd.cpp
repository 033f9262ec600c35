#include "solver/ccd.h"

#include <algorithm>
#include <cmath>

#include "potential/point_edge_distance.h"

namespace invfree {

namespace {

double distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  return std::sqrt(point_edge_distance_squared(p, a, b));
}

// The additive loop on the pair's relative motion: certified time, before rechecking.
double additive_ccd(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& dp, const Vec2& da,
                    const Vec2& db, double t_max) {
  const Vec2 mean = (dp + da + db) / 3.0;
  const Vec2 vp = dp - mean, va = da - mean, vb = db - mean;
  const double rate = vp.norm() + std::sqrt(std::max(va.squaredNorm(), vb.squaredNorm()));
  double d = distance(p, a, b);
  if (!(d > 0.0)) return 0.0;
  if (rate == 0.0) return t_max;
  const double gap = kCcdGapFraction * d;
  Vec2 xp = p, xa = a, xb = b;
  double t = 0.0;
  for (int it = 0; it < kCcdMaxIterations; ++it) {
    const double step = (1.0 - kCcdGapFraction) * d / rate;
    xp += step * vp;
    xa += step * va;
    xb += step * vb;
    d = distance(xp, xa, xb);
    if (t > 0.0 && d < gap) break;  // the first step is always taken: it keeps d >= gap
    t += step;
    if (t >= t_max) return t_max;
  }
  return t;
}

bool paths_overlap(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& dp, const Vec2& da,
                   const Vec2& db, double t) {
  const Vec2 p1 = p + t * dp, a1 = a + t * da, b1 = b + t * db;
  const Vec2 plo = p.cwiseMin(p1), phi = p.cwiseMax(p1);
  const Vec2 elo = a.cwiseMin(a1).cwiseMin(b).cwiseMin(b1);
  const Vec2 ehi = a.cwiseMax(a1).cwiseMax(b).cwiseMax(b1);
  return (plo.array() <= ehi.array()).all() && (elo.array() <= phi.array()).all();
}

}  // namespace

double point_edge_ccd(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& dp, const Vec2& da,
                      const Vec2& db, double t_max) {
  double t = additive_ccd(p, a, b, dp, da, db, t_max);
  // The caller's arithmetic, x + t dx, not the loop's accumulated positions.
  while (t > 0.0 && !(point_edge_distance_squared(p + t * dp, a + t * da, b + t * db) > 0.0))
    t *= 0.5;
  return t;
}

double self_contact_step(const Boundary& boundary, std::span<const PointEdgePair> pairs,
                         const VecX& x, const VecX& p, double alpha_max) {
  double alpha = alpha_max;
  for (const PointEdgePair& pair : pairs) {
    const int i = boundary.nodes[pair.node];
    const auto& e = boundary.edges[pair.edge];
    const Vec2 xp = x.segment<2>(2 * i), xa = x.segment<2>(2 * e[0]), xb = x.segment<2>(2 * e[1]);
    const Vec2 dp = p.segment<2>(2 * i), da = p.segment<2>(2 * e[0]), db = p.segment<2>(2 * e[1]);
    if (!paths_overlap(xp, xa, xb, dp, da, db, alpha)) continue;
    alpha = std::min(alpha, point_edge_ccd(xp, xa, xb, dp, da, db, alpha));
  }
  return alpha;
}

}  // namespace invfree
