// The boundary of a triangle mesh, the surface that self-contact works on, found once per
// mesh. Inputs: a mesh, possibly several bodies concatenated (append_body), and the first
// node of each body. Outputs:
//  - edges: every edge that belongs to one triangle only, as the half-edge of that triangle
//    when it is counter-clockwise (reversed when it is clockwise), so that walking from
//    edges[k][0] to edges[k][1] the body is on the left and the outward normal on the right;
//  - nodes: the nodes those edges touch, ascending; node_slot maps a mesh node to its index
//    in `nodes` (-1 inside the body);
//  - each node's contact area, half the rest lengths of its boundary edges (the tutorial's
//    side / n_seg on a square), and each node's and edge's body.
// Node indices in `edges` are the mesh's; a PointEdgePair names a boundary node by its slot
// in `nodes` and an edge by its index in `edges`.
#pragma once

#include <array>
#include <compare>
#include <span>
#include <vector>

#include "scene/mesh.h"

namespace invfree {

struct Boundary {
  std::vector<std::array<int, 2>> edges;  // mesh node indices, body on the left from [0] to [1]
  std::vector<int> edge_body;
  std::vector<int> nodes;  // mesh node indices, ascending
  std::vector<int> node_body;
  std::vector<double> node_area;  // m: half the rest lengths of the node's boundary edges
  std::vector<int> node_slot;     // per mesh node: its index in `nodes`, or -1
  int edge_count() const { return static_cast<int>(edges.size()); }
  int node_count() const { return static_cast<int>(nodes.size()); }
};

// A boundary node (its slot in Boundary::nodes) and a boundary edge (its index in
// Boundary::edges): the primitive pair of 2D point-edge contact.
struct PointEdgePair {
  int node = 0;
  int edge = 0;
  bool operator==(const PointEdgePair&) const = default;
  auto operator<=>(const PointEdgePair&) const = default;
};

// body_begin: the first node of each body, ascending, starting with 0 ({0}: one body).
Boundary find_boundary(const Mesh& mesh, std::span<const int> body_begin);
inline Boundary find_boundary(const Mesh& mesh) {
  return find_boundary(mesh, mesh.body_begin);
}

}  // namespace invfree
