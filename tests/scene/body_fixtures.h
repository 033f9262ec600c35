// Fixtures for the self-contact tests and benchmarks: a mesh's positions as the solver's
// flat vector (x, y per node), and two equal squares in one mesh, the second moved by an
// offset, with their boundary.
#pragma once

#include <vector>

#include "scene/boundary.h"

namespace invfree::test {

inline VecX flat_positions(const std::vector<Vec2>& points) {
  VecX x(2 * points.size());
  for (size_t i = 0; i < points.size(); ++i) x.segment<2>(2 * i) = points[i];
  return x;
}

struct TwoSquares {
  Mesh mesh;
  int second = 0;  // the second square's first node
  Boundary boundary;
};

inline TwoSquares two_squares(double side, int n_seg, const Vec2& offset) {
  TwoSquares out;
  const Mesh square = square_mesh(side, n_seg);
  const int first[] = {append_body(out.mesh, square, Vec2::Zero()),
                       append_body(out.mesh, square, offset)};
  out.second = first[1];
  out.boundary = find_boundary(out.mesh, first);
  return out;
}

}  // namespace invfree::test
