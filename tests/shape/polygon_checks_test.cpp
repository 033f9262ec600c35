// Loop validation (core/shape/polygon_checks.h): each problem's reason, exact decisions
// on touching and collinear cases, and the grid's speed on a 20,000-point loop.
#include "shape/polygon_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace invfree {
namespace {

Loop square(double x0, double y0, double s) {
  return {Vec2(x0, y0), Vec2(x0 + s, y0), Vec2(x0 + s, y0 + s), Vec2(x0, y0 + s)};
}

TEST(PolygonChecks, ValidLoopsPassEitherOrientation) {
  Loop l = square(0, 0, 1);
  EXPECT_EQ(check_loop(l, "outline"), "");
  std::reverse(l.begin(), l.end());
  EXPECT_EQ(check_loop(l, "outline"), "");
  EXPECT_DOUBLE_EQ(loop_signed_area(l), -1.0);
}

TEST(PolygonChecks, FewerThanThreePoints) {
  EXPECT_EQ(check_loop({Vec2(0, 0), Vec2(1, 0)}, "outline"), "outline: fewer than three points");
}

TEST(PolygonChecks, NotFinite) {
  Loop l = square(0, 0, 1);
  l[2].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(check_loop(l, "outline"), "outline: point 2 is not finite");
  l[2].y() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(check_loop(l, "holes[3]"), "holes[3]: point 2 is not finite");
  l[2].y() = 1e200;
  EXPECT_EQ(check_loop(l, "outline"), "outline: point 2 is out of range (|coordinate| > 1e100 m)");
}

TEST(PolygonChecks, ZeroAreaAndRepeatedPoints) {
  EXPECT_EQ(check_loop({Vec2(0, 0), Vec2(1, 1), Vec2(3, 3)}, "outline"), "outline: zero area");
  EXPECT_EQ(check_loop({Vec2(0, 0), Vec2(1, 0), Vec2(1, 0), Vec2(0, 1)}, "outline"),
            "outline: points 1 and 2 coincide");
}

TEST(PolygonChecks, SelfIntersectingBowTie) {
  // Edges 0 (0,0)-(1,1) and 2 (1,0)-(0,1) cross.
  EXPECT_EQ(check_loop({Vec2(0, 0), Vec2(1, 1), Vec2(1, 0), Vec2(0, 1)}, "outline"),
            "outline: edges 0 and 2 cross (self-intersecting)");
}

TEST(PolygonChecks, VertexTouchingAnEdgeIsSelfIntersecting) {
  // Point 4 (1, 0) lies on edge 0 (0,0)-(2,0): edges 0 and 3 touch.
  const Loop l{Vec2(0, 0), Vec2(2, 0), Vec2(2, 2), Vec2(1, 2), Vec2(1, 0), Vec2(0, 1)};
  EXPECT_EQ(check_loop(l, "outline"), "outline: edges 0 and 3 touch (self-intersecting)");
}

TEST(PolygonChecks, DoublingBackIsAnOverlap) {
  const Loop l{Vec2(0, 0), Vec2(2, 0), Vec2(1, 0), Vec2(1, 1)};
  EXPECT_EQ(check_loop(l, "outline"), "outline: edges 0 and 1 overlap (the loop doubles back)");
}

TEST(PolygonChecks, HolesInsideOutsideTouchingOverlapping) {
  const Loop outline = square(0, 0, 10);
  EXPECT_EQ(check_polygon_with_holes(outline, std::vector<Loop>{square(1, 1, 2), square(5, 5, 2)}),
            "");
  EXPECT_EQ(check_polygon_with_holes(outline, std::vector<Loop>{square(1, 1, 2), square(20, 1, 2)}),
            "holes[1]: not inside the outline");
  EXPECT_EQ(check_polygon_with_holes(outline, std::vector<Loop>{square(0, 1, 2)}),
            "holes[0]: touches the outline");
  EXPECT_EQ(check_polygon_with_holes(outline, std::vector<Loop>{square(-1, 1, 2)}),
            "holes[0]: crosses the outline");
  EXPECT_EQ(check_polygon_with_holes(
                outline, std::vector<Loop>{square(1, 1, 3), square(6, 6, 1), square(2, 2, 3)}),
            "holes[0] and holes[2] overlap");
  EXPECT_EQ(check_polygon_with_holes(outline, std::vector<Loop>{square(1, 1, 4), square(2, 2, 1)}),
            "holes[0] and holes[1] overlap");
  EXPECT_EQ(check_polygon_with_holes(outline, std::vector<Loop>{square(1, 1, 2), square(3, 1, 2)}),
            "holes[0] and holes[1] touch");
  // The outline's own problems come first.
  EXPECT_EQ(check_polygon_with_holes({Vec2(0, 0), Vec2(1, 0)}, std::vector<Loop>{}),
            "outline: fewer than three points");
}

TEST(PolygonChecks, PointInLoopIsExactOnTheBoundary) {
  const Loop l = square(0, 0, 1);
  EXPECT_EQ(point_in_loop(Vec2(0.5, 0.5), l), 1);
  EXPECT_EQ(point_in_loop(Vec2(1.0, 0.3), l), 0);
  EXPECT_EQ(point_in_loop(Vec2(std::nextafter(1.0, 2.0), 0.3), l), -1);
  EXPECT_EQ(winding_number(Vec2(0.5, 0.5), l), 1);
}

// Their cost is measured, not asserted: build/release/tests/shape/invfree_shape_bench
// --benchmark_filter=validate_outline.
TEST(PolygonChecks, TwentyThousandPointsPassAndOneCrossingIsNamed) {
  // A wavy circle of 20,000 points and a star whose edges all meet near the centre.
  const int n = 20000;
  Loop wavy(n), star(n);
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * k / n;
    const double r = 1 + 0.05 * std::sin(40 * t);
    wavy[k] = Vec2(r * std::cos(t), r * std::sin(t));
    const double rs = k % 2 ? 1.0 : 1e-3;
    star[k] = Vec2(rs * std::cos(t), rs * std::sin(t));
  }
  EXPECT_EQ(check_loop(wavy, "outline"), "");
  EXPECT_EQ(check_loop(star, "outline"), "");
  // One crossing in 20,000 points is found and named.
  std::swap(wavy[100], wavy[101]);
  EXPECT_EQ(check_loop(wavy, "outline"), "outline: edges 99 and 101 cross (self-intersecting)");
}

}  // namespace
}  // namespace invfree
