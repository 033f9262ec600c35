#include "potential/self_contact_clearance.h"

#include <algorithm>
#include <cmath>

namespace invfree {

void measure_clearance(const Boundary& boundary, const std::vector<Vec2>& rest, const VecX& x,
                       const SelfContactParams& params, BroadPhaseGrid& grid,
                       SelfContactClearance& out) {
  const int nb = boundary.node_count();
  out.at.resize(2 * nb);
  double largest = 0.0;
  for (int k = 0; k < nb; ++k) {
    out.at.segment<2>(2 * k) = x.segment<2>(2 * boundary.nodes[k]);
    largest = std::max(largest, out.at.segment<2>(2 * k).cwiseAbs().maxCoeff());
  }
  out.dhat = params.dhat;
  // Far above the rounding of a distance or a displacement (a few ulps of the coordinates).
  out.margin = 1e-9 * (1.0 + largest);
  out.pairs.clear();
  out.pair_slack.clear();
  if (boundary.edge_count() == 0 || !out.at.allFinite()) {
    out.slack = out.far = boundary.edge_count() == 0 ? INFINITY : -INFINITY;
    return;
  }
  // Reach: dhat plus the mean rest edge length (node_area sums to the boundary's length),
  // so that the pairs not listed leave about as much slack as neighbours along the
  // boundary do anyway.
  double length = 0.0;
  for (double a : boundary.node_area) length += a;
  const double reach = params.dhat + length / boundary.edge_count();
  point_edge_candidates(boundary, x, reach, grid, out.pairs);
  out.far = reach - params.dhat;
  out.slack = out.far;
  for (const PointEdgePair& pair : out.pairs) {
    const int i = boundary.nodes[pair.node];
    const auto& e = boundary.edges[pair.edge];
    const double d = std::sqrt(point_edge_distance_squared(
        x.segment<2>(2 * i), x.segment<2>(2 * e[0]), x.segment<2>(2 * e[1])));
    const bool same_body = boundary.node_body[pair.node] == boundary.edge_body[pair.edge];
    const double rest_distance =
        same_body ? std::sqrt(point_edge_distance_squared(rest[i], rest[e[0]], rest[e[1]])) : 0.0;
    const double g = d - pair_dhat(params.dhat, rest_distance, same_body);
    out.pair_slack.push_back(g);
    out.slack = std::min(out.slack, g);
  }
}

double clearance_motion(const Boundary& boundary, SelfContactClearance& c, const VecX& z,
                        const VecX* p, double alpha) {
  const int nb = boundary.node_count();
  if (c.at.size() != 2 * nb || !(c.slack > -INFINITY)) return INFINITY;
  // The displacements' box over the whole motion; t, their common translation, its middle.
  const auto ends = [&](int k, Vec2& a, Vec2& b) {
    const int i = boundary.nodes[k];
    a = z.segment<2>(2 * i) - c.at.segment<2>(2 * k);
    b = p ? Vec2(a + alpha * p->segment<2>(2 * i)) : a;
  };
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
  for (int k = 0; k < nb; ++k) {
    Vec2 a, b;
    ends(k, a, b);
    lo = lo.cwiseMin(a).cwiseMin(b);
    hi = hi.cwiseMax(a).cwiseMax(b);
  }
  if (!lo.allFinite() || !hi.allFinite()) return INFINITY;
  // Every displacement is within half that box's diagonal of t: enough where the motion is
  // small (the usual case, nothing close), and then no node's own box is needed.
  const double quick = 0.5 * (hi - lo).norm();
  if (2.0 * quick + c.margin < c.slack) return quick;
  // Otherwise each node's box (near_pairs reads them), and its farthest corner from t.
  const Vec2 t = 0.5 * (lo + hi);
  c.lo.resize(nb);
  c.hi.resize(nb);
  double m2 = 0.0;
  for (int k = 0; k < nb; ++k) {
    Vec2 a, b;
    ends(k, a, b);
    c.lo[k] = a.cwiseMin(b);
    c.hi[k] = a.cwiseMax(b);
    m2 = std::max(m2, (c.lo[k] - t).cwiseAbs().cwiseMax((c.hi[k] - t).cwiseAbs()).squaredNorm());
  }
  return std::sqrt(m2);
}

bool near_pairs(const Boundary& boundary, const SelfContactClearance& c, double dhat, double m,
                std::vector<PointEdgePair>& out) {
  out.clear();
  if (c.dhat != dhat || !(2.0 * m + c.margin < c.far) ||
      c.lo.size() != static_cast<size_t>(boundary.node_count()))
    return false;
  // The largest distance between a point of box j and a point of box k, squared.
  const auto apart2 = [&](int j, int k) {
    return (c.hi[j] - c.lo[k]).cwiseAbs().cwiseMax((c.lo[j] - c.hi[k]).cwiseAbs()).squaredNorm();
  };
  const size_t count = c.pairs.size();
  for (size_t q = 0; q < count; ++q) {
    const double g = c.pair_slack[q] - c.margin;
    if (2.0 * m < g) continue;  // the global bound already keeps it out
    const PointEdgePair& pair = c.pairs[q];
    // The edge's ends by their boundary slots (every boundary edge's ends are boundary nodes).
    const auto& e = boundary.edges[pair.edge];
    const double rel2 = std::max(apart2(boundary.node_slot[e[0]], pair.node),
                                 apart2(boundary.node_slot[e[1]], pair.node));
    if (g > 0.0 && rel2 < g * g) continue;
    out.push_back(pair);
  }
  return true;
}

}  // namespace invfree
