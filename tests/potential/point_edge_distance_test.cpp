// The squared point-edge distance: value against a brute-force search along the edge,
// gradient and Hessian against central differences in each regime (including points within
// 1e-5 of a regime switch and near-degenerate shapes), and C1 continuity across the switch.
#include "potential/point_edge_distance.h"

#include <gtest/gtest.h>

#include "tests/potential/point_edge_samples.h"
#include "tests/test_support.h"

namespace invfree {
namespace {

using test::PointEdgeSample;

double distance_squared(const Vec6& x) {
  return point_edge_distance_squared(x.segment<2>(0), x.segment<2>(2), x.segment<2>(4));
}
PointEdgeRegime regime(const Vec6& x) {
  return point_edge_regime(x.segment<2>(0), x.segment<2>(2), x.segment<2>(4));
}
Vec6 gradient(const Vec6& x) {
  return point_edge_distance_squared_gradient(x.segment<2>(0), x.segment<2>(2), x.segment<2>(4),
                                              regime(x));
}

// True when every central-difference point around x has x's regime.
bool stencil_in_one_regime(const Vec6& x, double eps) {
  for (int k = 0; k < 6; ++k)
    for (double s : {-eps, eps}) {
      Vec6 y = x;
      y[k] += s;
      if (regime(y) != regime(x)) return false;
    }
  return true;
}

double scale_of(const PointEdgeSample& s) {
  return std::max((s.b - s.a).norm(), (s.p - s.a).norm());
}

TEST(PointEdgeDistance, ValueIsTheMinimumOverTheEdge) {
  for (const PointEdgeSample& s : test::point_edge_samples(600, 1)) {
    const double d2 = point_edge_distance_squared(s.p, s.a, s.b);
    constexpr int kSamples = 20000;
    double best = INFINITY;
    for (int k = 0; k <= kSamples; ++k)
      best = std::min(best, (s.p - (s.a + (k / double(kSamples)) * (s.b - s.a))).squaredNorm());
    // The minimum is no larger than any sample, and within half a sample spacing of the best.
    const double spacing = 0.5 * (s.b - s.a).norm() / kSamples;
    EXPECT_LE(d2, best * (1.0 + 1e-12) + 1e-300);
    EXPECT_LE(std::sqrt(best), std::sqrt(d2) * (1.0 + 1e-12) + spacing * 1.0001);
  }
}

TEST(PointEdgeDistance, RegimesAreTheClosestFeature) {
  const Vec2 a(0.0, 0.0), b(2.0, 0.0);
  EXPECT_EQ(point_edge_regime(Vec2(-0.1, 1.0), a, b), PointEdgeRegime::FirstEnd);
  EXPECT_EQ(point_edge_regime(Vec2(2.1, 1.0), a, b), PointEdgeRegime::SecondEnd);
  EXPECT_EQ(point_edge_regime(Vec2(1.0, -1.0), a, b), PointEdgeRegime::Interior);
  EXPECT_EQ(point_edge_regime(Vec2(1.0, 1.0), a, a), PointEdgeRegime::FirstEnd);
  EXPECT_DOUBLE_EQ(point_edge_distance_squared(Vec2(1.0, -3.0), a, b), 9.0);
  EXPECT_DOUBLE_EQ(point_edge_distance_squared(Vec2(-3.0, 4.0), a, b), 25.0);
  EXPECT_DOUBLE_EQ(point_edge_distance_squared(Vec2(5.0, 4.0), a, b), 25.0);
  EXPECT_DOUBLE_EQ(point_edge_closest_parameter(Vec2(0.5, 7.0), a, b, PointEdgeRegime::Interior),
                   0.25);
}

TEST(PointEdgeDistance, GradientAndHessianMatchFiniteDifferences) {
  int checked[3] = {0, 0, 0}, hessians = 0;
  for (const PointEdgeSample& s : test::point_edge_samples(3000, 2)) {
    const Vec6 x = test::stack(s);
    const double eps = 1e-7 * scale_of(s);
    const std::function<double(const Vec6&)> f = distance_squared;
    const Vec6 g = gradient(x);
    const Vec6 fd = test::fd_gradient(f, x, eps);
    // D is C1 everywhere, so the gradient check needs no care at the switch.
    EXPECT_LE((g - fd).norm(), 1e-6 * g.norm() + 1e-9 * scale_of(s) * scale_of(s))
        << s.p.transpose() << " | " << s.a.transpose() << " | " << s.b.transpose();
    ++checked[static_cast<int>(regime(x))];
    if (!stencil_in_one_regime(x, eps)) continue;
    ++hessians;
    const Mat6 h = point_edge_distance_squared_hessian(s.p, s.a, s.b, regime(x));
    const Mat6 fdh = test::fd_jacobian(gradient, x, eps);
    EXPECT_LE((h - fdh).norm(), 1e-6 * h.norm() + 1e-9) << s.p.transpose();
    EXPECT_LE((h - h.transpose()).norm(), 1e-12 * h.norm());
  }
  for (int r = 0; r < 3; ++r) EXPECT_GT(checked[r], 300) << "regime " << r;
  EXPECT_GT(hessians, 2900);
}

TEST(PointEdgeDistance, ValueAndGradientAreContinuousAcrossTheSwitch) {
  std::mt19937 rng(3);
  for (int k = 0; k < 200; ++k) {
    const double end = k % 2 ? 1.0 : 0.0, h = 0.3 + 0.01 * k;
    std::mt19937 copy = rng;
    const PointEdgeSample before = test::point_edge_at(rng, 0.7, end - 1e-9, h);
    const PointEdgeSample after = test::point_edge_at(copy, 0.7, end + 1e-9, h);
    ASSERT_NE(regime(test::stack(before)), regime(test::stack(after)));
    const double d0 = distance_squared(test::stack(before)),
                 d1 = distance_squared(test::stack(after));
    EXPECT_NEAR(d0, d1, 1e-8 * d0);
    EXPECT_LE((gradient(test::stack(before)) - gradient(test::stack(after))).norm(), 1e-7);
  }
}

}  // namespace
}  // namespace invfree
