// Validation of a triangle mesh given as a file (shape = "mesh": ShapeDef::loaded's nodes
// and triangles, used as given). Each problem is one reason naming the first offender by
// index, "file: triangle 12 is inverted (clockwise where the others are
// counter-clockwise)". Checked in this order:
//  - at least one triangle; every node index in range; every node finite;
//  - no degenerate triangle: a repeated node, or twice the area <= kDegenerateArea times
//    the square of the mesh's bounding box's longer side (exactly zero by the exact
//    orientation predicate counts too);
//  - no duplicate triangles (the same three nodes in any order);
//  - no unused node;
//  - every edge in at most two triangles, and two triangles sharing an edge lie on its
//    two sides (same orientation, opposite directions) rather than folded onto one side;
//  - one orientation: a mesh whose triangles are all clockwise is flipped to
//    counter-clockwise; a mix is an error naming the first triangle against the majority
//    (the first triangle's orientation on a tie).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "shape/shape.h"
#include "types.h"

namespace invfree {

inline constexpr double kDegenerateArea = 1e-12;

struct CheckedMesh {
  std::vector<Vec2> nodes;                    // as given
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise (flipped when all were not)
  bool flipped = false;                       // every triangle was clockwise
  std::string error;                          // "" when valid
};

CheckedMesh check_mesh(const ShapeFile& file);

}  // namespace invfree
