// Shape regions (core/shape/shape_region.h): the analytic shapes' loops and roles, the
// svg fill rules through the nesting tree, bounds, areas and the keys' reasons.
#include "shape/shape_region.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "shape/polygon_checks.h"

namespace invfree {
namespace {

Loop square(double x0, double y0, double s, bool ccw = true) {
  Loop l{Vec2(x0, y0), Vec2(x0 + s, y0), Vec2(x0 + s, y0 + s), Vec2(x0, y0 + s)};
  if (!ccw) std::reverse(l.begin(), l.end());
  return l;
}

ShapeDef svg(std::vector<Loop> loops, FillRule rule) {
  ShapeDef s;
  s.kind = ShapeKind::Svg;
  s.loaded.loops = std::move(loops);
  s.loaded.fill_rule = rule;
  return s;
}

TEST(ShapeRegion, RingIsAnOuterCircleAndAHole) {
  ShapeDef s;
  s.kind = ShapeKind::Ring;
  s.radius = 1.0;
  s.inner_radius = 0.4;
  const ShapeRegion r = shape_region(s, 0.1);
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.loops.size(), 2u);
  EXPECT_FALSE(r.loops[0].hole);
  EXPECT_TRUE(r.loops[1].hole);
  EXPECT_GT(loop_signed_area(r.loops[0].points), 0);
  EXPECT_LT(loop_signed_area(r.loops[1].points), 0);
  EXPECT_EQ(static_cast<int>(r.loops[0].points.size()), circle_segments(1.0, 0.1));
  EXPECT_EQ(circle_segments(1.0, 0.1), 64);   // ceil(2 pi / 0.1) = 63, up to a multiple of 4
  EXPECT_EQ(circle_segments(0.01, 0.1), 12);  // at least 12
  for (const RegionLoop& l : r.loops)
    for (std::size_t k = 0; k < l.points.size(); ++k)
      EXPECT_LE((l.points[k] - l.points[(k + 1) % l.points.size()]).norm(), 0.1);
}

TEST(ShapeRegion, KeysAreValidated) {
  ShapeDef s;
  s.kind = ShapeKind::Rectangle;
  s.width = 0;
  EXPECT_EQ(validate_shape(s), "width: must be finite and > 0");
  s.width = 1;
  s.height = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validate_shape(s), "height: must be finite and > 0");
  s.kind = ShapeKind::Disk;
  s.radius = -1;
  EXPECT_EQ(validate_shape(s), "radius: must be finite and > 0");
  s.kind = ShapeKind::Ring;
  s.radius = 1;
  s.inner_radius = 1;
  EXPECT_EQ(validate_shape(s), "inner_radius: must be < radius");
  s.inner_radius = std::nan("");
  EXPECT_EQ(validate_shape(s), "inner_radius: must be finite and > 0");
  EXPECT_EQ(shape_region(svg({}, FillRule::NonZero), 0.1).error, "file: no closed path is filled");
}

TEST(ShapeRegion, SvgNonZeroAndEvenOdd) {
  // Three nested squares, all counter-clockwise: nonzero fills everything (only the
  // outermost loop bounds the region); evenodd fills the outer band and the innermost.
  const std::vector<Loop> nested{square(-3, -3, 6), square(-2, -2, 4), square(-1, -1, 2)};
  ShapeRegion nz = shape_region(svg(nested, FillRule::NonZero), 1.0);
  ASSERT_EQ(nz.error, "");
  ASSERT_EQ(nz.loops.size(), 1u);
  EXPECT_DOUBLE_EQ(shape_area(svg(nested, FillRule::NonZero)), 36.0);
  ShapeRegion eo = shape_region(svg(nested, FillRule::EvenOdd), 1.0);
  ASSERT_EQ(eo.loops.size(), 3u);
  EXPECT_FALSE(eo.loops[0].hole);
  EXPECT_TRUE(eo.loops[1].hole);
  EXPECT_FALSE(eo.loops[2].hole);
  EXPECT_DOUBLE_EQ(shape_area(svg(nested, FillRule::EvenOdd)), 36.0 - 16.0 + 4.0);
  // Nonzero with the middle loop reversed: it cuts a hole, the inner one (winding 0 -> +1
  // inside) fills again.
  const std::vector<Loop> reversed{square(-3, -3, 6), square(-2, -2, 4, false), square(-1, -1, 2)};
  EXPECT_DOUBLE_EQ(shape_area(svg(reversed, FillRule::NonZero)), 36.0 - 16.0 + 4.0);
  // Side-by-side paths are two outer loops.
  EXPECT_DOUBLE_EQ(shape_area(svg({square(0, 0, 1), square(2, 0, 1)}, FillRule::NonZero)), 2.0);
}

TEST(ShapeRegion, CrossingSvgPathsAreAnError) {
  EXPECT_EQ(shape_region(svg({square(0, 0, 2), square(1, 1, 2)}, FillRule::NonZero), 1.0).error,
            "file: paths[0] and paths[1] cross");
  EXPECT_EQ(shape_region(svg({square(0, 0, 2), square(2, 0, 2)}, FillRule::NonZero), 1.0).error,
            "file: paths[0] and paths[1] touch");
}

TEST(ShapeRegion, BoundsAreaAndMaxEdge) {
  ShapeDef s;
  s.kind = ShapeKind::Rectangle;
  s.width = 4;
  s.height = 1;
  EXPECT_EQ(shape_bounds(s).min(), Vec2(-2, -0.5));
  EXPECT_EQ(shape_bounds(s).max(), Vec2(2, 0.5));
  EXPECT_DOUBLE_EQ(shape_max_edge(s, 8), 0.5);
  s.max_edge = 0.3;
  EXPECT_DOUBLE_EQ(shape_max_edge(s, 8), 0.3);
  EXPECT_DOUBLE_EQ(shape_area(s), 4.0);
  s.kind = ShapeKind::Disk;
  s.radius = 2;
  EXPECT_DOUBLE_EQ(shape_area(s), 4 * std::numbers::pi);
  s.kind = ShapeKind::Polygon;
  s.outline = square(0, 0, 10, false);
  s.holes = {square(1, 1, 2), square(5, 5, 3, false)};
  EXPECT_DOUBLE_EQ(shape_area(s), 100.0 - 4.0 - 9.0);
  EXPECT_EQ(shape_bounds(s).max(), Vec2(10, 10));
  EXPECT_TRUE(shape_bounds(ShapeDef{}).isEmpty());
  EXPECT_TRUE(std::isnan(shape_area(ShapeDef{})));
}

}  // namespace
}  // namespace invfree
