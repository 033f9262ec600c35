// The line-search filters of the terms that bound a step: the inversion-free filter
// (potential/elasticity.h) and the plane filter (potential/plane_barrier.h).
#include <gtest/gtest.h>

#include <random>

#include "potential/incremental_potential.h"
#include "scene/mesh.h"

namespace invfree {
namespace {

TEST(SmallestPositiveRoot, Cases) {
  EXPECT_DOUBLE_EQ(smallest_positive_root(1, -3, 2), 1.0);   // roots 1, 2
  EXPECT_DOUBLE_EQ(smallest_positive_root(1, 1, -2), 1.0);   // roots -2, 1
  EXPECT_TRUE(std::isinf(smallest_positive_root(1, 3, 2)));  // roots -1, -2
  EXPECT_TRUE(std::isinf(smallest_positive_root(1, 0, 1)));  // complex
  EXPECT_DOUBLE_EQ(smallest_positive_root(0, -2, 1), 0.5);   // linear
  EXPECT_TRUE(std::isinf(smallest_positive_root(0, 0, 1)));  // constant
  // Tiny a: the naive formula would divide by ~0 and lose the small root to cancellation.
  EXPECT_NEAR(smallest_positive_root(1e-20, -1.0, 0.9), 0.9, 1e-15);
  EXPECT_NEAR(smallest_positive_root(-1e-20, -1.0, 0.9), 0.9, 1e-15);
}

double signed_area(const VecX& x, const std::array<int, 3>& t) {
  const Vec2 a = x.segment<2>(2 * t[1]) - x.segment<2>(2 * t[0]);
  const Vec2 b = x.segment<2>(2 * t[2]) - x.segment<2>(2 * t[0]);
  return a.x() * b.y() - a.y() * b.x();
}

TEST(InversionFreeStep, NeverInvertsOverRandomDirections) {
  const Mesh mesh = square_mesh(1.0, 6);
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0, 1);
  for (int trial = 0; trial < 300; ++trial) {
    VecX x(2 * mesh.node_count()), p(x.size());
    for (int i = 0; i < mesh.node_count(); ++i) x.segment<2>(2 * i) = mesh.rest[i];
    const double scale = std::pow(10.0, trial % 4 - 2);  // 0.01 .. 10 times the mesh size
    for (int k = 0; k < p.size(); ++k) p[k] = scale * g(rng);
    const double alpha = inversion_free_step(mesh, x, p);
    ASSERT_GT(alpha, 0.0);
    ASSERT_LE(alpha, 1.0);
    // Everywhere on [0, alpha] every triangle keeps more than 10% of its area.
    for (double f : {0.25, 0.5, 0.75, 1.0}) {
      const VecX y = x + f * alpha * p;
      for (const auto& t : mesh.triangles) {
        ASSERT_GT(signed_area(y, t), 0.1 * signed_area(x, t) * (1 - 1e-9));
      }
    }
  }
}

TEST(InversionFreeStep, FullStepWhenSafe) {
  const Mesh mesh = square_mesh(1.0, 2);
  VecX x(2 * mesh.node_count());
  for (int i = 0; i < mesh.node_count(); ++i) x.segment<2>(2 * i) = mesh.rest[i];
  const VecX p = 0.1 * x;  // uniform growth
  EXPECT_DOUBLE_EQ(inversion_free_step(mesh, x, p), 1.0);
  EXPECT_NEAR(inversion_free_step(mesh, x, -2.0 * x), (1 - std::sqrt(0.1)) / 2, 1e-12);
}

TEST(PlaneStep, NeverCrossesOverRandomDirections) {
  const int n = 40;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  GroundBarrier ground;
  ground.on = true;
  ground.y0 = -1.0;
  CeilingBarrier ceiling;
  ceiling.on = true;
  for (int trial = 0; trial < 300; ++trial) {
    VecX x(2 * n + 1), p(2 * n + 1);
    x[2 * n] = 1.0;
    for (int i = 0; i < n; ++i) {
      x[2 * i] = u(rng);
      x[2 * i + 1] = 0.999 * u(rng);
    }
    for (int k = 0; k < p.size(); ++k) p[k] = 3.0 * u(rng);
    const double alpha = plane_step(ground, ceiling, n, x, p);
    ASSERT_GT(alpha, 0.0);
    const VecX y = x + alpha * p;
    for (int i = 0; i < n; ++i) {
      ASSERT_GE(y[2 * i + 1] - (-1.0), 0.1 * (x[2 * i + 1] + 1.0) * (1 - 1e-12));
      ASSERT_GE(y[2 * n] - y[2 * i + 1], 0.1 * (x[2 * n] - x[2 * i + 1]) * (1 - 1e-12));
    }
  }
}

}  // namespace
}  // namespace invfree
