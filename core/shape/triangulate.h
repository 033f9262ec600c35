// Quality triangulation of a region (shape/shape_region.h) by CGAL's 2D constrained
// Delaunay mesher (Constrained_Delaunay_triangulation_2 + Delaunay_mesher_2 with
// Delaunay_mesh_size_criteria_2). This is the one translation unit of the project that
// includes CGAL (GPL-3.0-or-later; its compile time stays in one object).
// What CGAL guarantees for the in-domain triangles once refinement ends:
//  - size: every edge of every triangle is <= max_edge (a triangle whose longest edge
//    exceeds the size bound is "imperatively bad" and always refined), up to the rounding
//    of CGAL's squared-length computation (a relative 1e-15);
//  - shape: sin^2 of every triangle's smallest angle is >= kShapeBound = 0.125 (CGAL's
//    shape bound B is compared with (2 area)^2 / (l_max^2 l_mid^2) = sin^2 of the smallest
//    angle, Delaunay_mesh_criteria_2.h), i.e. a smallest angle >= asin(sqrt(0.125)) =
//    20.705 degrees, except in triangles near an input corner sharper than 60 degrees,
//    which Delaunay refinement cannot improve (CGAL's clusters leave such triangles
//    alone so that refinement ends; Shewchuk 2002).
// Boundary points may be added on the loops' edges (midpoints of split constraints); no
// point is moved or dropped. Output is deterministic: the same loops and max_edge give the
// same nodes and triangles bit for bit (points inserted one by one in loop order, no
// random choice; nodes renumbered by a Morton key).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "shape/shape_region.h"
#include "types.h"

namespace invfree {

inline constexpr double kShapeBound = 0.125;

struct Triangulation {
  std::vector<Vec2> nodes;                    // Morton order of the node positions
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise, sorted
  long refinement_steps = 0;                  // the mesher's steps taken
  std::string error;                          // "" on success; nothing is thrown
};

// Meshes the region bounded by `loops` (pairwise disjoint, validated; the domain is
// marked by nesting parity, which the roles of a valid region agree with) with edges
// <= max_edge. More than max_steps refinement steps (each inserts at most one point)
// stops with an error instead of running on.
Triangulation triangulate_region(const std::vector<RegionLoop>& loops, double max_edge,
                                 long max_steps);

// Whether `loop` (>= 3 finite points) is a simple polygon: CGAL::is_simple_2, a sweep in
// O(n log n) with exact predicates. nullopt in a build without CGAL.
std::optional<bool> loop_is_simple(const Loop& loop);

}  // namespace invfree
