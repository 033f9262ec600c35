// The self-contact invariant of an accepted state, checked like det F > 0: no two boundary
// edges intersect, two edges that share a node meeting only there. Exact for double
// coordinates: every decision is the sign of an orientation (collision/orientation.h,
// exact by expansion arithmetic) or a comparison of input coordinates, never a distance
// against a tolerance. The invariant also means every boundary node is at a positive
// distance from every boundary edge not incident to it: a node on such an edge makes its
// own edges touch that edge (point_on_segment is the test).
// Inputs: the boundary, positions x (2 per mesh node), the broad phase's grid and a scratch
// list (reused, no allocation once grown). Outputs: the first offending pair of edges, or
// none; and the smallest point-edge distance among candidate pairs (the CSV's min_self_gap).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "collision/broad_phase.h"

namespace invfree {

// Closed segments; exact.
bool point_on_segment(const Vec2& p, const Vec2& a, const Vec2& b);
bool segments_intersect(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1);
// Segments s-a and s-c sharing the end s overlap beyond it: collinear and on the same side.
bool shared_end_segments_overlap(const Vec2& s, const Vec2& a, const Vec2& c);

struct SelfIntersection {
  int edge_a = -1, edge_b = -1;  // boundary edge indices, edge_a < edge_b
};

std::optional<SelfIntersection> find_self_intersection(const Boundary& boundary, const VecX& x,
                                                       BroadPhaseGrid& grid,
                                                       std::vector<std::array<int, 2>>& scratch);

// Smallest distance from a node to an edge over the pairs (+infinity for none), in metres.
double min_self_gap(const Boundary& boundary, std::span<const PointEdgePair> pairs, const VecX& x);

}  // namespace invfree
