#include "collision/intersection_check.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/orientation.h"
#include "potential/point_edge_distance.h"

namespace invfree {

namespace {

// p inside the axis-aligned box of a and b (comparisons of inputs: exact).
bool in_box(const Vec2& p, const Vec2& a, const Vec2& b) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

}  // namespace

bool point_on_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  return orientation(a, b, p) == 0 && in_box(p, a, b);
}

bool segments_intersect(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1) {
  const int o1 = orientation(a0, a1, b0), o2 = orientation(a0, a1, b1);
  const int o3 = orientation(b0, b1, a0), o4 = orientation(b0, b1, a1);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;  // proper crossing
  // Touching: an end on the other segment (collinear and inside its box).
  return (o1 == 0 && in_box(b0, a0, a1)) || (o2 == 0 && in_box(b1, a0, a1)) ||
         (o3 == 0 && in_box(a0, b0, b1)) || (o4 == 0 && in_box(a1, b0, b1));
}

bool shared_end_segments_overlap(const Vec2& s, const Vec2& a, const Vec2& c) {
  // Collinear, and one far end lies on the other segment (a zero-length one included).
  return orientation(s, a, c) == 0 && (in_box(a, s, c) || in_box(c, s, a));
}

std::optional<SelfIntersection> find_self_intersection(const Boundary& boundary, const VecX& x,
                                                       BroadPhaseGrid& grid,
                                                       std::vector<std::array<int, 2>>& scratch) {
  edge_edge_candidates(boundary, x, grid, scratch);
  const auto at = [&](int node) -> Vec2 { return x.segment<2>(2 * node); };
  for (const auto& [ea, eb] : scratch) {
    const auto& e = boundary.edges[ea];
    const auto& f = boundary.edges[eb];
    bool hit;
    if ((e[0] == f[0] && e[1] == f[1]) || (e[0] == f[1] && e[1] == f[0]))
      hit = true;  // the same segment twice
    else if (e[0] == f[0] || e[0] == f[1])
      hit = shared_end_segments_overlap(at(e[0]), at(e[1]), at(e[0] == f[0] ? f[1] : f[0]));
    else if (e[1] == f[0] || e[1] == f[1])
      hit = shared_end_segments_overlap(at(e[1]), at(e[0]), at(e[1] == f[0] ? f[1] : f[0]));
    else
      hit = segments_intersect(at(e[0]), at(e[1]), at(f[0]), at(f[1]));
    if (hit) return SelfIntersection{ea, eb};
  }
  return std::nullopt;
}

double min_self_gap(const Boundary& boundary, std::span<const PointEdgePair> pairs, const VecX& x) {
  double gap2 = std::numeric_limits<double>::infinity();
  for (const PointEdgePair& pair : pairs) {
    const int i = boundary.nodes[pair.node];
    const auto& e = boundary.edges[pair.edge];
    gap2 = std::min(gap2, point_edge_distance_squared(x.segment<2>(2 * i), x.segment<2>(2 * e[0]),
                                                      x.segment<2>(2 * e[1])));
  }
  return std::sqrt(gap2);
}

}  // namespace invfree
