// Meshing shapes (core/shape/shape_mesh.h, triangulate.h): the mesh covers exactly the
// shape (area, boundary loops and their orientation, holes empty), its triangles meet the
// documented angle and edge bounds, the output is bit-identical across runs and threads,
// and every bad input comes back as one reason, fast, without an exception.
#include "shape/shape_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <thread>

#include "scene/boundary.h"
#include "shape/polygon_checks.h"
#include "shape/shape_region.h"
#include "shape/triangulate.h"

namespace invfree {
namespace {

Loop square(double x0, double y0, double s, bool ccw = true) {
  Loop l{Vec2(x0, y0), Vec2(x0 + s, y0), Vec2(x0 + s, y0 + s), Vec2(x0, y0 + s)};
  if (!ccw) std::reverse(l.begin(), l.end());
  return l;
}

ShapeDef rectangle() {
  ShapeDef s;
  s.kind = ShapeKind::Rectangle;
  s.width = 2.0;
  s.height = 1.0;
  return s;
}
ShapeDef disk() {
  ShapeDef s;
  s.kind = ShapeKind::Disk;
  s.radius = 0.5;
  return s;
}
ShapeDef ring() {
  ShapeDef s;
  s.kind = ShapeKind::Ring;
  s.radius = 0.5;
  s.inner_radius = 0.3;
  return s;
}
// A plate with a square hole and a triangular hole, outline clockwise, holes mixed.
ShapeDef plate() {
  ShapeDef s;
  s.kind = ShapeKind::Polygon;
  s.outline = square(-1, -0.5, 2, false);
  s.outline = {Vec2(-1, -0.5), Vec2(-1, 0.5), Vec2(1, 0.5), Vec2(1, -0.5)};
  s.holes = {square(-0.7, -0.2, 0.4), {Vec2(0.3, -0.3), Vec2(0.7, -0.3), Vec2(0.5, 0.2)}};
  return s;
}

double twice_area(const Mesh& m, const std::array<int, 3>& t) {
  const Vec2 u = m.rest[t[1]] - m.rest[t[0]], v = m.rest[t[2]] - m.rest[t[0]];
  return u.x() * v.y() - u.y() * v.x();
}

double mesh_area(const Mesh& m) {
  double a = 0;
  for (const auto& t : m.triangles) a += 0.5 * twice_area(m, t);
  return a;
}

double smallest_angle_degrees(const Mesh& m) {
  double smallest = 180;
  for (const auto& t : m.triangles)
    for (int i = 0; i < 3; ++i) {
      const Vec2 a = m.rest[t[(i + 1) % 3]] - m.rest[t[i]];
      const Vec2 b = m.rest[t[(i + 2) % 3]] - m.rest[t[i]];
      const double angle = std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
      smallest = std::min(smallest, angle * 180 / std::numbers::pi);
    }
  return smallest;
}

double longest_edge(const Mesh& m) {
  double longest = 0;
  for (const auto& t : m.triangles)
    for (int i = 0; i < 3; ++i)
      longest = std::max(longest, (m.rest[t[i]] - m.rest[t[(i + 1) % 3]]).norm());
  return longest;
}

// The boundary's edges chained into loops; each loop's signed area (outer > 0, hole < 0).
// Fails the test when a loop does not close (a node with other than one edge out and in).
std::vector<double> boundary_loop_areas(const Mesh& m) {
  const Boundary b = find_boundary(m);
  std::map<int, int> next;
  std::map<int, int> in_count;
  for (const auto& e : b.edges) {
    EXPECT_TRUE(next.emplace(e[0], e[1]).second) << "node " << e[0] << " starts two edges";
    ++in_count[e[1]];
  }
  for (const auto& [node, count] : in_count) EXPECT_EQ(count, 1) << "node " << node;
  std::vector<double> areas;
  std::map<int, bool> seen;
  for (const auto& [start, _] : next) {
    if (seen[start]) continue;
    Loop loop;
    int v = start;
    do {
      seen[v] = true;
      loop.push_back(m.rest[v]);
      v = next.at(v);
    } while (v != start && loop.size() <= next.size());
    EXPECT_EQ(v, start) << "open boundary loop";
    areas.push_back(loop_signed_area(loop));
  }
  return areas;
}

bool in_some_triangle(const Mesh& m, const Vec2& p) {
  for (const auto& t : m.triangles) {
    bool inside = true;
    for (int i = 0; i < 3; ++i) {
      const Vec2 a = m.rest[t[i]], b = m.rest[t[(i + 1) % 3]];
      if ((b - a).x() * (p - a).y() - (b - a).y() * (p - a).x() < 0) inside = false;
    }
    if (inside) return true;
  }
  return false;
}

void expect_quality(const ShapeDef& shape, double max_edge, int outers, int holes) {
  const ShapeMeshResult r = mesh_shape(shape, max_edge);
  ASSERT_EQ(r.error, "");
  const Mesh& m = r.mesh;
  ASSERT_GT(m.triangle_count(), 0);
  ASSERT_EQ(m.rest_area.size(), m.triangles.size());
  for (const auto& t : m.triangles) EXPECT_GT(twice_area(m, t), 0) << "clockwise triangle";
  EXPECT_GE(smallest_angle_degrees(m), kMinAngleDegrees);
  // CGAL's size bound compares squared lengths in doubles: a relative 1e-15 of slack.
  EXPECT_LE(longest_edge(m), max_edge * (1 + 1e-12));
  const std::vector<double> areas = boundary_loop_areas(m);
  EXPECT_EQ(std::count_if(areas.begin(), areas.end(), [](double a) { return a > 0; }), outers);
  EXPECT_EQ(std::count_if(areas.begin(), areas.end(), [](double a) { return a < 0; }), holes);
  const double exact = shape_area(shape);
  const double bound = region_area_error_bound(shape, max_edge);
  EXPECT_NEAR(mesh_area(m), exact, bound + 1e-12 * exact);
  // Every node is used by a triangle.
  std::vector<char> used(m.node_count(), 0);
  for (const auto& t : m.triangles)
    for (int v : t) used[v] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
}

TEST(ShapeMesh, RectangleAreaAnglesEdgesBoundary) {
  expect_quality(rectangle(), 0.1, 1, 0);
  EXPECT_NEAR(mesh_area(mesh_shape(rectangle(), 0.1).mesh), 2.0, 2e-12);
}
TEST(ShapeMesh, DiskWithinTheSagittaBound) {
  expect_quality(disk(), 0.05, 1, 0);
  // The bound is not empty: the inscribed polygon really is short of pi r^2.
  const double a = mesh_area(mesh_shape(disk(), 0.05).mesh);
  EXPECT_LT(a, std::numbers::pi * 0.25);
  EXPECT_GT(a, std::numbers::pi * 0.25 - region_area_error_bound(disk(), 0.05));
}
TEST(ShapeMesh, RingHasOneHole) {
  expect_quality(ring(), 0.04, 1, 1);
  EXPECT_FALSE(in_some_triangle(mesh_shape(ring(), 0.04).mesh, Vec2(0, 0)));
  EXPECT_FALSE(in_some_triangle(mesh_shape(ring(), 0.04).mesh, Vec2(0.29, 0)));
}
TEST(ShapeMesh, PolygonWithHolesExactArea) {
  expect_quality(plate(), 0.05, 1, 2);
  const Mesh m = mesh_shape(plate(), 0.05).mesh;
  EXPECT_NEAR(mesh_area(m), 2.0 - 0.16 - 0.1, 1e-12 * 1.74);
  EXPECT_FALSE(in_some_triangle(m, Vec2(-0.5, 0.0)));
  EXPECT_FALSE(in_some_triangle(m, Vec2(0.5, -0.1)));
  EXPECT_TRUE(in_some_triangle(m, Vec2(0.0, 0.0)));
}
TEST(ShapeMesh, SvgEvenOddNestedSquares) {
  ShapeDef s;
  s.kind = ShapeKind::Svg;
  s.loaded.loops = {square(-3, -3, 6), square(-2, -2, 4), square(-1, -1, 2)};
  s.loaded.fill_rule = FillRule::EvenOdd;
  expect_quality(s, 0.4, 2, 1);
  const Mesh m = mesh_shape(s, 0.4).mesh;
  EXPECT_TRUE(in_some_triangle(m, Vec2(0, 0)));
  EXPECT_FALSE(in_some_triangle(m, Vec2(1.5, 0)));
  EXPECT_TRUE(in_some_triangle(m, Vec2(2.5, 0)));
}
TEST(ShapeMesh, MeshFileUsedAsGivenAndFlipped) {
  ShapeDef s;
  s.kind = ShapeKind::MeshFile;
  s.loaded.nodes = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  s.loaded.triangles = {{0, 2, 1}, {0, 3, 2}};
  const ShapeMeshResult r = mesh_shape(s, 0.1);
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.mesh.rest, s.loaded.nodes);
  EXPECT_EQ(r.mesh.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_DOUBLE_EQ(r.mesh.rest_area[0] + r.mesh.rest_area[1], 1.0);
}

TEST(ShapeMesh, DeterministicAcrossRunsAndThreads) {
  const ShapeDef s = plate();
  const ShapeRegion region = shape_region(s, 0.02);
  ASSERT_EQ(region.error, "");
  const Triangulation first = triangulate_region(region.loops, 0.02, 10'000'000);
  ASSERT_EQ(first.error, "");
  auto same = [&](const Triangulation& t) {
    ASSERT_EQ(t.nodes.size(), first.nodes.size());
    EXPECT_EQ(t.triangles, first.triangles);
    EXPECT_EQ(std::memcmp(t.nodes.data(), first.nodes.data(), t.nodes.size() * sizeof(Vec2)), 0);
  };
  same(triangulate_region(region.loops, 0.02, 10'000'000));
  Triangulation a, b;
  std::thread ta([&] { a = triangulate_region(region.loops, 0.02, 10'000'000); });
  std::thread tb([&] { b = triangulate_region(region.loops, 0.02, 10'000'000); });
  ta.join();
  tb.join();
  same(a);
  same(b);
  // mesh_shape from two threads at once (cache and all) gives the same mesh.
  ShapeMeshResult ra, rb;
  std::thread tc([&] { ra = mesh_shape(ring(), 0.013); });
  std::thread td([&] { rb = mesh_shape(ring(), 0.013); });
  tc.join();
  td.join();
  EXPECT_EQ(ra.error, "");
  EXPECT_EQ(ra.mesh.triangles, rb.mesh.triangles);
  EXPECT_EQ(ra.mesh.rest, rb.mesh.rest);
}

TEST(ShapeMesh, BadInputsGiveOneReason) {
  ShapeDef s;
  s.kind = ShapeKind::Polygon;
  s.outline = {Vec2(0, 0), Vec2(1, 1), Vec2(1, 0), Vec2(0, 1)};
  EXPECT_EQ(mesh_shape(s, 0.1).error, "outline: edges 0 and 2 cross (self-intersecting)");
  s.outline = square(0, 0, 1);
  s.holes = {square(2, 0, 0.5)};
  EXPECT_EQ(mesh_shape(s, 0.1).error, "holes[0]: not inside the outline");
  s.holes = {square(0, 0.2, 0.5)};
  EXPECT_EQ(mesh_shape(s, 0.1).error, "holes[0]: touches the outline");
  s.holes = {};
  s.outline = {Vec2(0, 0), Vec2(1, 0)};
  EXPECT_EQ(mesh_shape(s, 0.1).error, "outline: fewer than three points");
  s.outline = {Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)};
  EXPECT_EQ(mesh_shape(s, 0.1).error, "outline: zero area");
  s.outline = {Vec2(0, 0), Vec2(1, 0), Vec2(std::nan(""), 1)};
  EXPECT_EQ(mesh_shape(s, 0.1).error, "outline: point 2 is not finite");
  s.outline = {Vec2(0, 0), Vec2(1, 0), Vec2(1, std::numeric_limits<double>::infinity())};
  EXPECT_EQ(mesh_shape(s, 0.1).error, "outline: point 2 is not finite");
  s.outline = square(0, 0, 1);
  EXPECT_EQ(mesh_shape(s, 0.0).error, "max_edge: must be finite and > 0");
  EXPECT_EQ(mesh_shape(s, std::nan("")).error, "max_edge: must be finite and > 0");

  ShapeDef svg;
  svg.kind = ShapeKind::Svg;
  svg.loaded.loops = {square(0, 0, 2), square(1, 1, 2)};
  EXPECT_EQ(mesh_shape(svg, 0.1).error, "file: paths[0] and paths[1] cross");
  svg.loaded.loops = {};
  EXPECT_EQ(mesh_shape(svg, 0.1).error, "file: no closed path is filled");

  ShapeDef mesh;
  mesh.kind = ShapeKind::MeshFile;
  mesh.loaded.nodes = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  mesh.loaded.triangles = {{0, 1, 2}, {0, 2, 3}, {2, 0, 1}};
  EXPECT_EQ(mesh_shape(mesh, 0.1).error,
            "file: triangles 0 and 2 are duplicates (the same three nodes)");
  mesh.loaded.triangles = {{0, 1, 2}, {0, 3, 2}};
  EXPECT_EQ(mesh_shape(mesh, 0.1).error,
            "file: triangle 1 is inverted (clockwise where the others are counter-clockwise)");
  mesh.loaded.nodes.push_back(Vec2(2, 2));
  mesh.loaded.triangles = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_EQ(mesh_shape(mesh, 0.1).error, "file: node 4 is used by no triangle");
  mesh.loaded.triangles.push_back({0, 2, 4});
  EXPECT_EQ(mesh_shape(mesh, 0.1).error, "file: triangle 2 is degenerate (zero area)");

  ShapeDef bad_ring = ring();
  bad_ring.inner_radius = 0.6;
  EXPECT_EQ(mesh_shape(bad_ring, 0.1).error, "inner_radius: must be < radius");
  EXPECT_EQ(mesh_shape(ShapeDef{}, 0.1).error.rfind("shape: ", 0), 0u);
}

// Refused from the area estimate, before any meshing (no time limit here: a test asserts
// no wall-clock figure; ctest's timeout catches a hang).
TEST(ShapeMesh, MaxEdgeOverTheCapIsRefusedBeforeMeshing) {
  const ShapeMeshResult r = mesh_shape(disk(), 1e-5);
  EXPECT_EQ(r.error,
            "max_edge: 1e-05 m would give about 40,000,000,000 triangles, more than the cap of "
            "2,000,000");
  EXPECT_EQ(r.mesh.triangle_count(), 0);
  EXPECT_EQ(mesh_shape(rectangle(), 1e-300).error,
            "max_edge: 1e-300 m would give far more triangles than the cap of 2,000,000");
}

TEST(ShapeMesh, EstimateIsNearTheCount) {
  for (const ShapeDef& s : {rectangle(), disk(), ring(), plate()}) {
    const double max_edge = 0.02;
    const ShapeMeshResult r = mesh_shape(s, max_edge);
    ASSERT_EQ(r.error, "");
    const double ratio = r.mesh.triangle_count() / estimated_triangle_count(s, max_edge);
    std::printf("%s: %d triangles, estimate ratio %.3f\n", enum_name(kShapeKindNames, s.kind),
                r.mesh.triangle_count(), ratio);
    EXPECT_GT(ratio, 0.9) << enum_name(kShapeKindNames, s.kind);
    EXPECT_LT(ratio, 1.1) << enum_name(kShapeKindNames, s.kind);
  }
}

TEST(ShapeMesh, SharpInputCornerStillEnds) {
  // A 5-degree wedge: refinement cannot lift the angle at its tip, but ends (CGAL's
  // clusters), and the mesh still covers the wedge exactly.
  ShapeDef s;
  s.kind = ShapeKind::Polygon;
  const double t = 5 * std::numbers::pi / 180;
  s.outline = {Vec2(0, 0), Vec2(1, 0), Vec2(std::cos(t), std::sin(t))};
  const ShapeMeshResult r = mesh_shape(s, 0.05);
  ASSERT_EQ(r.error, "");
  EXPECT_NEAR(mesh_area(r.mesh), shape_area(s), 1e-12 * shape_area(s));
  EXPECT_LE(longest_edge(r.mesh), 0.05 * (1 + 1e-12));
}

TEST(ShapeMesh, RunawayRefinementStopsWithAnError) {
  // 1000 m by 1 mm at max_edge 1 m: the area estimate is 5 triangles, but good angles in
  // the strip need about two million; the step budget stops it with this error (ctest's
  // timeout would catch a hang; no wall-clock figure is asserted).
  ShapeDef s;
  s.kind = ShapeKind::Rectangle;
  s.width = 1000;
  s.height = 1e-3;
  const ShapeMeshResult r = mesh_shape(s, 1.0);
  EXPECT_EQ(r.error.rfind("max_edge: meshing stopped after ", 0), 0u) << r.error;
  EXPECT_EQ(r.mesh.triangle_count(), 0);
}

}  // namespace
}  // namespace invfree
