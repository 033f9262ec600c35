#include "scene/mesh.h"

#include <gtest/gtest.h>

namespace invfree {
namespace {

TEST(SquareMesh, NumberingMatchesTheLecture) {
  const int n_seg = 4;
  const Mesh m = square_mesh(1.0, n_seg);
  ASSERT_EQ(m.node_count(), 25);
  ASSERT_EQ(m.triangle_count(), 32);
  for (int i = 0; i <= n_seg; ++i)
    for (int j = 0; j <= n_seg; ++j) {
      EXPECT_DOUBLE_EQ(m.rest[i * 5 + j].x(), -0.5 + i * 0.25);
      EXPECT_DOUBLE_EQ(m.rest[i * 5 + j].y(), -0.5 + j * 0.25);
    }
  // Cell (0,0): (0^0) = 0, the "else" pattern; cell (0,1): the alternating one.
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{0, 5, 6}));
  EXPECT_EQ(m.triangles[1], (std::array<int, 3>{0, 6, 1}));
  EXPECT_EQ(m.triangles[2], (std::array<int, 3>{1, 6, 2}));
  EXPECT_EQ(m.triangles[3], (std::array<int, 3>{6, 7, 2}));
}

TEST(SquareMesh, RestDataIsPositiveAndConsistent) {
  for (int n_seg : {1, 3, 8}) {
    const Mesh m = square_mesh(2.0, n_seg);
    double area = 0;
    for (int t = 0; t < m.triangle_count(); ++t) {
      EXPECT_GT(m.rest_area[t], 0.0);
      area += m.rest_area[t];
      const auto& tri = m.triangles[t];
      Mat2 b;
      b.col(0) = m.rest[tri[1]] - m.rest[tri[0]];
      b.col(1) = m.rest[tri[2]] - m.rest[tri[0]];
      EXPECT_LT((b * m.rest_shape_inverse[t] - Mat2::Identity()).norm(), 1e-14);
    }
    EXPECT_NEAR(area, 4.0, 1e-12);
  }
}

TEST(NodeMasses, UniformAndLumpedBothConserveTotalMass) {
  const Mesh m = square_mesh(1.0, 4);
  for (MassMode mode : {MassMode::Uniform, MassMode::Lumped}) {
    const auto mass = node_masses(m, 1000.0, mode);
    double total = 0;
    for (double v : mass) total += v;
    EXPECT_NEAR(total, 1000.0, 1e-9);
  }
  const auto uniform = node_masses(m, 1000.0, MassMode::Uniform);
  EXPECT_DOUBLE_EQ(uniform[0], 1000.0 / 25);
  const auto lumped = node_masses(m, 1000.0, MassMode::Lumped);
  EXPECT_LT(lumped[0], lumped[12]);  // a corner node carries less than an interior one
  // Node 12 = (i, j) = (2, 2): all four surrounding cells put their diagonal through it.
  EXPECT_NEAR(lumped[12], 1000.0 * 8 * (0.25 * 0.25 / 2) / 3, 1e-9);
}

}  // namespace
}  // namespace invfree
