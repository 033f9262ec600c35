// Mesh file validation (core/shape/mesh_check.h): each bad mesh's reason names the first
// offender; an all-clockwise mesh is flipped.
#include "shape/mesh_check.h"

#include <gtest/gtest.h>

#include <limits>

namespace invfree {
namespace {

// A unit square of two counter-clockwise triangles, plus a third square to the right.
ShapeFile two_squares() {
  ShapeFile f;
  f.nodes = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1), Vec2(2, 0), Vec2(2, 1)};
  f.triangles = {{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 2}};
  return f;
}

TEST(MeshCheck, ValidMeshPassesAsGiven) {
  const CheckedMesh m = check_mesh(two_squares());
  EXPECT_EQ(m.error, "");
  EXPECT_FALSE(m.flipped);
  EXPECT_EQ(m.triangles, two_squares().triangles);
}

TEST(MeshCheck, AllClockwiseIsFlipped) {
  ShapeFile f = two_squares();
  for (auto& t : f.triangles) std::swap(t[0], t[1]);
  const CheckedMesh m = check_mesh(f);
  EXPECT_EQ(m.error, "");
  EXPECT_TRUE(m.flipped);
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{1, 2, 0}));
}

TEST(MeshCheck, Inverted) {
  ShapeFile f = two_squares();
  std::swap(f.triangles[2][1], f.triangles[2][2]);
  EXPECT_EQ(check_mesh(f).error,
            "file: triangle 2 is inverted (clockwise where the others are counter-clockwise)");
}

TEST(MeshCheck, Degenerate) {
  ShapeFile f = two_squares();
  f.nodes.push_back(Vec2(3, 0));
  f.triangles.push_back({4, 6, 4});
  EXPECT_EQ(check_mesh(f).error, "file: triangle 4 is degenerate (a node repeated)");
  f.triangles.back() = {1, 4, 6};  // three points on y = 0
  EXPECT_EQ(check_mesh(f).error, "file: triangle 4 is degenerate (zero area)");
  f.nodes.back() = Vec2(3, 1e-13);  // near-zero relative to the mesh's size
  EXPECT_EQ(check_mesh(f).error, "file: triangle 4 is degenerate (zero area)");
}

TEST(MeshCheck, Duplicate) {
  ShapeFile f = two_squares();
  f.triangles.push_back({2, 0, 1});
  EXPECT_EQ(check_mesh(f).error, "file: triangles 0 and 4 are duplicates (the same three nodes)");
}

TEST(MeshCheck, UnusedNode) {
  ShapeFile f = two_squares();
  f.nodes.push_back(Vec2(5, 5));
  EXPECT_EQ(check_mesh(f).error, "file: node 6 is used by no triangle");
}

TEST(MeshCheck, EmptyRangeAndFinite) {
  ShapeFile f = two_squares();
  f.triangles.clear();
  EXPECT_EQ(check_mesh(f).error, "file: no triangle");
  f = two_squares();
  f.triangles[1][2] = 9;
  EXPECT_EQ(check_mesh(f).error, "file: triangle 1 refers to node 9, but there are 6 nodes");
  f = two_squares();
  f.nodes[3].x() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(check_mesh(f).error, "file: node 3 is not finite");
}

TEST(MeshCheck, NonManifoldAndFolded) {
  ShapeFile f = two_squares();
  f.nodes.push_back(Vec2(0.5, -1));
  f.triangles.push_back({0, 6, 1});  // edge 0-1 now in three triangles? no: two, fine
  EXPECT_EQ(check_mesh(f).error, "");
  f.nodes.push_back(Vec2(0.5, -2));
  f.triangles.push_back({0, 7, 1});  // a third triangle on edge 0-1
  EXPECT_EQ(check_mesh(f).error,
            "file: edge 0-1 is shared by more than two triangles (non-manifold)");
  f = two_squares();
  f.nodes.push_back(Vec2(0.5, 0.2));
  f.triangles.push_back({0, 1, 6});  // on the same side of 0->1 as triangle 0
  EXPECT_EQ(check_mesh(f).error,
            "file: triangles 0 and 4 overlap (both on the same side of edge 0-1)");
}

}  // namespace
}  // namespace invfree
