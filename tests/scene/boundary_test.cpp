// Boundaries of square meshes: 4 n_seg edges and nodes, one closed counter-clockwise loop
// with the body on the left of every edge, the interior excluded, contact areas side/n_seg;
// clockwise triangles give the same loop; two bodies keep their own loops and indices.
#include "scene/boundary.h"

#include <gtest/gtest.h>

#include <map>

namespace invfree {
namespace {

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Checks that the edges of `body` form one loop around it, counter-clockwise, with every
// edge's own triangle on its left; returns the loop's enclosed area (shoelace).
double check_loop(const Mesh& mesh, const Boundary& boundary, int body) {
  std::map<int, int> next;
  for (int k = 0; k < boundary.edge_count(); ++k) {
    if (boundary.edge_body[k] != body) continue;
    const auto& e = boundary.edges[k];
    EXPECT_TRUE(next.emplace(e[0], e[1]).second) << "two edges leave node " << e[0];
    // The triangle holding the edge lies on its left.
    for (const auto& tri : mesh.triangles)
      for (int c = 0; c < 3; ++c)
        if ((tri[c] == e[0] && tri[(c + 1) % 3] == e[1]) ||
            (tri[c] == e[1] && tri[(c + 1) % 3] == e[0])) {
          const int other = tri[(c + 2) % 3];
          EXPECT_GT(cross(mesh.rest[e[1]] - mesh.rest[e[0]], mesh.rest[other] - mesh.rest[e[0]]),
                    0.0);
        }
  }
  const int start = next.begin()->first;
  int node = start, steps = 0;
  double area = 0.0;
  do {
    const int to = next.at(node);
    area += 0.5 * cross(mesh.rest[node], mesh.rest[to]);
    node = to;
    ++steps;
  } while (node != start && steps <= static_cast<int>(next.size()));
  EXPECT_EQ(steps, static_cast<int>(next.size())) << "not a single loop";
  return area;
}

TEST(Boundary, SquareMeshesHaveOneCounterClockwiseLoop) {
  for (int n_seg : {1, 2, 3, 4, 7, 16}) {
    const double side = 0.45;
    const Mesh mesh = square_mesh(side, n_seg);
    const Boundary b = find_boundary(mesh);
    ASSERT_EQ(b.edge_count(), 4 * n_seg);
    ASSERT_EQ(b.node_count(), 4 * n_seg);
    EXPECT_NEAR(check_loop(mesh, b, 0), side * side, 1e-14);
    EXPECT_TRUE(std::is_sorted(b.nodes.begin(), b.nodes.end()));
    for (int n = 0; n < b.node_count(); ++n) {
      const Vec2 x = mesh.rest[b.nodes[n]];
      EXPECT_NEAR(std::max(std::abs(x.x()), std::abs(x.y())), side / 2, 1e-15);  // on the square
      EXPECT_NEAR(b.node_area[n], side / n_seg, 1e-15);
      EXPECT_EQ(b.node_slot[b.nodes[n]], n);
      EXPECT_EQ(b.node_body[n], 0);
    }
    int interior = 0;
    for (int v = 0; v < mesh.node_count(); ++v) interior += b.node_slot[v] < 0;
    EXPECT_EQ(interior, (n_seg - 1) * (n_seg - 1));
  }
}

TEST(Boundary, ClockwiseTrianglesGiveTheSameLoop) {
  const Mesh mesh = square_mesh(1.0, 3);
  Mesh flipped = mesh;
  for (auto& tri : flipped.triangles) std::swap(tri[1], tri[2]);
  compute_rest_data(flipped);
  const Boundary a = find_boundary(mesh), b = find_boundary(flipped);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.nodes, b.nodes);
}

TEST(Boundary, TwoBodiesKeepTheirLoopsAndIndices) {
  Mesh mesh;
  const Mesh small = square_mesh(0.45, 2), fine = square_mesh(0.45, 5);
  const int first[] = {append_body(mesh, small, Vec2::Zero()),
                       append_body(mesh, fine, Vec2(0.045, -0.495))};
  EXPECT_EQ(first[1], 9);
  ASSERT_EQ(mesh.node_count(), 9 + 36);
  ASSERT_EQ(mesh.triangle_count(), 8 + 50);
  EXPECT_EQ(mesh.rest[9 + 7], fine.rest[7] + Vec2(0.045, -0.495));
  EXPECT_EQ(mesh.rest_shape_inverse[8 + 3], fine.rest_shape_inverse[3]);
  const Boundary b = find_boundary(mesh, first);
  ASSERT_EQ(b.edge_count(), 8 + 20);
  EXPECT_NEAR(check_loop(mesh, b, 0), 0.45 * 0.45, 1e-14);
  EXPECT_NEAR(check_loop(mesh, b, 1), 0.45 * 0.45, 1e-14);
  for (int k = 0; k < b.edge_count(); ++k) {
    const int body = b.edges[k][0] >= 9;
    EXPECT_EQ(b.edge_body[k], body);
    EXPECT_EQ(b.edges[k][1] >= 9, body);
  }
  for (int n = 0; n < b.node_count(); ++n) {
    EXPECT_EQ(b.node_body[n], b.nodes[n] >= 9);
    EXPECT_NEAR(b.node_area[n], b.node_body[n] ? 0.45 / 5 : 0.45 / 2, 1e-15);
  }
}

}  // namespace
}  // namespace invfree
