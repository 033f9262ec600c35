// first_failing_triangle (core/potential/first_failing_triangle.h): the lowest failing
// index, as a serial scan finds it, for any thread count, with the mesh split into several
// blocks of triangles.
#include "potential/first_failing_triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "linalg/parallel.h"
#include "scene/mesh.h"

namespace invfree {
namespace {

int serial_first(const Mesh& mesh, const VecX& x, bool (*ok)(double)) {
  for (int t = 0; t < mesh.triangle_count(); ++t)
    if (!ok(triangle_deformation_gradient(mesh, x.data(), t).determinant())) return t;
  return -1;
}

bool positive(double det) {
  return det > 0.0;
}
bool finite(double det) {
  return std::isfinite(det);
}

// Node (i, j) of a square_mesh with n_seg segments, as it numbers them.
int node_at(const Mesh& mesh, int i, int j) {
  const int n = static_cast<int>(std::lround(std::sqrt(mesh.node_count()))) - 1;
  return j * (n + 1) + i;
}

TEST(FirstFailingTriangle, TheLowestIndexOverSeveralBlocksForAnyThreadCount) {
  const Mesh mesh = square_mesh(1.0, 64);  // 8,192 triangles: two blocks or more
  ASSERT_GE(split_blocks(mesh.triangle_count(), kTriangleBlock, kMaxBlocks).blocks, 2);
  VecX rest(2 * mesh.node_count());
  for (int v = 0; v < mesh.node_count(); ++v) rest.segment<2>(2 * v) = mesh.rest[v];

  // A node in the upper rows pulled far down inverts triangles of the last block only; a
  // second one in the lower rows inverts some of the first block as well.
  VecX upper = rest;
  const int high = node_at(mesh, 20, 50);
  upper[2 * high + 1] -= 0.2;
  VecX both = upper;
  const int low = node_at(mesh, 40, 10);
  both[2 * low + 1] -= 0.2;
  VecX not_finite = rest;
  not_finite[2 * node_at(mesh, 7, 40)] = std::numeric_limits<double>::quiet_NaN();

  const int expected_upper = serial_first(mesh, upper, positive);
  const int expected_both = serial_first(mesh, both, positive);
  const int expected_nan = serial_first(mesh, not_finite, finite);
  const int first_block_end = split_blocks(mesh.triangle_count(), kTriangleBlock, kMaxBlocks).size;
  ASSERT_GE(expected_upper, first_block_end) << "the upper node must fail in a later block";
  ASSERT_GE(expected_both, 0);
  ASSERT_LT(expected_both, first_block_end);
  ASSERT_GE(expected_nan, 0);

  for (int threads : {1, 2, 3}) {
    set_thread_count(threads);
    EXPECT_EQ(first_failing_triangle(mesh, rest.data(), positive), -1) << threads;
    EXPECT_EQ(first_failing_triangle(mesh, upper.data(), positive), expected_upper) << threads;
    EXPECT_EQ(first_failing_triangle(mesh, both.data(), positive), expected_both) << threads;
    EXPECT_EQ(first_failing_triangle(mesh, not_finite.data(), finite), expected_nan) << threads;
  }
  set_thread_count(0);
}

}  // namespace
}  // namespace invfree
