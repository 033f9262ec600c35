// Validation of closed polygons (shape/shape.h's Loop) before they are meshed: each check
// returns "" when the loops are fine and otherwise one short reason naming the first
// problem, its subject spelt as the caller names it ("outline: edges 3 and 9 cross
// (self-intersecting)", "holes[1]: not inside the outline"). Pure geometry: every
// incidence (crossing, touching, inside) is decided by the exact orientation predicate
// (collision/orientation.h), so a reported problem is a true one and a loop that passes
// can be given to CGAL's constrained triangulation as pairwise non-crossing constraints.
// Cost: whether each loop is simple is CGAL's sweep (CGAL::is_simple_2, O(n log n), via
// shape/triangulate.h); the edge pairs are searched (and decided exactly) only to name the
// pair of a loop that is not simple and between loops, in a quadtree whose leaves hold at
// most 24 segments and which is only refined where two loops meet a box. 20,000 points
// take milliseconds, a star of 20,000 points whose edges crowd its centre too; naming the
// crossing of a non-simple star of that size can take seconds (tests/shape/).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "shape/shape.h"
#include "types.h"

namespace invfree {

// One loop on its own: at least three points, every coordinate finite and at most 1e100
// in magnitude (the exact predicate's range), no two consecutive
// points equal, not all points on one line ("zero area"), and no two edges meeting except
// consecutive edges at their shared point (touching, crossing or overlapping is reported
// with both edge indices; edge i joins point i to point i+1, the last one back to 0).
// `name` prefixes the reason: "outline: fewer than three points".
std::string check_loop(const Loop& loop, const std::string& name);

// Several loops, each checked by check_loop, then pairwise: no edge of one loop may touch
// or cross an edge of another ("<name a> and <name b> touch" / "... cross"). Loops that
// pass are pairwise disjoint closed curves, nested or side by side.
std::string check_disjoint_loops(std::span<const Loop> loops, std::span<const std::string> names);

// A polygon with holes (shape = "polygon"): the outline and every hole pass
// check_disjoint_loops; every hole lies inside the outline ("holes[1]: not inside the
// outline"; one touching the outline: "holes[0]: touches the outline") and no hole lies
// inside another ("holes[0] and holes[2] overlap").
std::string check_polygon_with_holes(const Loop& outline, std::span<const Loop> holes);

// The signed area of a loop (positive counter-clockwise): the shoelace sum taken about the
// first point, which keeps the rounding relative to the loop's size, not its position.
double loop_signed_area(const Loop& loop);

// +1 when `p` is strictly inside the loop, 0 on it, -1 outside (exact; either orientation).
int point_in_loop(const Vec2& p, const Loop& loop);

// The winding number of the loop around `p` (not on the loop), exact.
int winding_number(const Vec2& p, const Loop& loop);

}  // namespace invfree
