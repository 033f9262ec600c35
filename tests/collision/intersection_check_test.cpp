// Exact orientation against integer arithmetic on nearly collinear points (where the plain
// floating-point determinant gets signs wrong), segment tests on every touching case, and
// the mesh invariant: a square at rest passes; a node through an edge, a node exactly on an
// edge, two edges folded flat onto each other, and two overlapping bodies are caught.
#include "collision/intersection_check.h"

#include <gtest/gtest.h>

#include <random>
#include <utility>

#include "collision/orientation.h"
#include "tests/scene/body_fixtures.h"

namespace invfree {
namespace {

// Coordinates k * 2^-40 with |k| < 2^45 are exact doubles; the determinant of their integer
// numerators fits in 128 bits.
constexpr double kGrid = 0x1p-40;

__extension__ typedef __int128 Int128;  // GCC's 128-bit integer (not ISO C++)

int reference_orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  const auto n = [](double v) { return static_cast<Int128>(std::llround(v / kGrid)); };
  const Int128 det =
      (n(b.x()) - n(a.x())) * (n(c.y()) - n(a.y())) - (n(b.y()) - n(a.y())) * (n(c.x()) - n(a.x()));
  return (det > 0) - (det < 0);
}

// Grid offsets (in units of kGrid) of b and c from a: exactly collinear ones, and lattice
// vectors with cross product +-1 (the smallest nonzero determinant, 2^-80, far below the
// rounding of the plain formula), found by the extended Euclidean algorithm.
struct Offsets {
  long long bx, by, cx, cy;
};

Offsets collinear_offsets(std::mt19937_64& rng) {
  std::uniform_int_distribution<long long> dir(-(1LL << 20), 1LL << 20), k(-(1LL << 22), 1LL << 22);
  const long long dx = dir(rng), dy = dir(rng), k1 = k(rng), k2 = k(rng);
  return {k1 * dx, k1 * dy, k2 * dx, k2 * dy};
}

Offsets unit_cross_offsets(std::mt19937_64& rng) {
  std::uniform_int_distribution<long long> big(1, 1LL << 40), small(-4, 4);
  for (;;) {
    const long long p = big(rng), q = big(rng);
    // Extended Euclid: x p + y q = gcd(p, q).
    long long r0 = p, r1 = q, x0 = 1, x1 = 0, y0 = 0, y1 = 1;
    while (r1 != 0) {
      const long long t = r0 / r1;
      r0 = std::exchange(r1, r0 - t * r1);
      x0 = std::exchange(x1, x0 - t * x1);
      y0 = std::exchange(y1, y0 - t * y1);
    }
    if (r0 != 1) continue;
    // b - a = (p, q), c - a = (-y0, x0) + m (p, q): cross = p x0 + q y0 = 1.
    const long long m = small(rng);
    const int flip = small(rng) > 0 ? -1 : 1;
    return {p, q, flip * (-y0 + m * p), flip * (x0 + m * q)};
  }
}

TEST(Orientation, ExactOnNearlyCollinearPoints) {
  std::mt19937_64 rng(14);
  std::uniform_int_distribution<long long> coordinate(-(1LL << 43), 1LL << 43);
  const auto grid_point = [&](long long x, long long y) { return Vec2(x * kGrid, y * kGrid); };
  int naive_wrong = 0, zero = 0;
  for (int k = 0; k < 100000; ++k) {
    const long long ax = coordinate(rng), ay = coordinate(rng);
    const Offsets o = k % 2 ? collinear_offsets(rng) : unit_cross_offsets(rng);
    const Vec2 a = grid_point(ax, ay), b = grid_point(ax + o.bx, ay + o.by),
               c = grid_point(ax + o.cx, ay + o.cy);
    const int expected = reference_orientation(a, b, c);
    ASSERT_EQ(expected == 0, k % 2 == 1);
    ASSERT_EQ(orientation(a, b, c), expected) << k;
    ASSERT_EQ(orientation_exact(a, b, c), expected) << k;
    ASSERT_EQ(orientation(b, c, a), expected);
    ASSERT_EQ(orientation(b, a, c), -expected);
    const double naive = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    naive_wrong += ((naive > 0) - (naive < 0)) != expected;
    zero += expected == 0;
  }
  EXPECT_GT(naive_wrong, 10000);  // not vacuous: the plain determinant fails here
  EXPECT_EQ(zero, 50000);
}

TEST(Orientation, ShewchuksFloatExample) {
  // Points p near (0.5, 0.5) on a 2^-53 grid against the line y = x through (12, 12) and
  // (24, 24): p, q, r turn counter-clockwise exactly when p lies above the line, y > x.
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const Vec2 p(0.5 + i * 0x1p-53, 0.5 + j * 0x1p-53);
      const int expected = (j > i) - (j < i);
      ASSERT_EQ(orientation(p, Vec2(12, 12), Vec2(24, 24)), expected) << i << " " << j;
    }
}

TEST(SegmentTests, EveryKindOfContact) {
  const Vec2 o(0, 0), x1(1, 0);
  EXPECT_TRUE(segments_intersect(o, x1, Vec2(0.5, -1), Vec2(0.5, 1)));        // crossing
  EXPECT_TRUE(segments_intersect(o, x1, Vec2(0.5, 0), Vec2(0.5, 1)));         // T at an end
  EXPECT_TRUE(segments_intersect(o, x1, Vec2(1, 0), Vec2(2, 1)));             // end on end
  EXPECT_TRUE(segments_intersect(o, x1, Vec2(0.5, 0), Vec2(2, 0)));           // collinear overlap
  EXPECT_TRUE(segments_intersect(o, x1, Vec2(0.3, 0), Vec2(0.3, 0)));         // a point on it
  EXPECT_FALSE(segments_intersect(o, x1, Vec2(1.5, 0), Vec2(2, 0)));          // collinear apart
  EXPECT_FALSE(segments_intersect(o, x1, Vec2(0, 1e-300), Vec2(1, 1e-300)));  // parallel
  EXPECT_FALSE(segments_intersect(o, x1, Vec2(0.5, 1e-17), Vec2(0.6, 1)));    // just above
  EXPECT_FALSE(segments_intersect(o, x1, Vec2(1 + 0x1p-52, -1), Vec2(1 + 0x1p-52, 1)));
  EXPECT_TRUE(point_on_segment(Vec2(0.25, 0), o, x1));
  EXPECT_FALSE(point_on_segment(Vec2(0.25, 1e-300), o, x1));
  // A point on the segment from (0.1, 0.2) to (0.7, 1.4) exactly: (0.4, 0.8) is not a double
  // on that line in general, so test with an exact dyadic slope instead.
  EXPECT_TRUE(point_on_segment(Vec2(0.375, 0.75), Vec2(0.125, 0.25), Vec2(0.625, 1.25)));
  // Shared end: folded flat onto each other, or a straight or bent continuation.
  EXPECT_TRUE(shared_end_segments_overlap(o, x1, Vec2(0.5, 0)));
  EXPECT_TRUE(shared_end_segments_overlap(o, x1, Vec2(3, 0)));
  EXPECT_FALSE(shared_end_segments_overlap(o, x1, Vec2(-1, 0)));
  EXPECT_FALSE(shared_end_segments_overlap(o, x1, Vec2(1, 1e-300)));
}

TEST(IntersectionCheck, CatchesEveryViolationOfTheInvariant) {
  const Mesh mesh = square_mesh(1.0, 4);  // nodes i * 5 + j at (-0.5 + i/4, -0.5 + j/4)
  const Boundary boundary = find_boundary(mesh);
  BroadPhaseGrid grid;
  std::vector<std::array<int, 2>> scratch;
  const VecX rest = test::flat_positions(mesh.rest);
  EXPECT_FALSE(find_self_intersection(boundary, rest, grid, scratch));

  VecX x = rest;
  const int top_middle = 2 * 5 + 4, bottom_second = 1 * 5 + 0;
  x.segment<2>(2 * top_middle) = Vec2(0.1, -0.6);  // through the bottom side
  EXPECT_TRUE(find_self_intersection(boundary, x, grid, scratch));
  x.segment<2>(2 * top_middle) = Vec2(0.125, -0.5);  // exactly on a bottom edge: distance 0
  EXPECT_TRUE(find_self_intersection(boundary, x, grid, scratch));
  x.segment<2>(2 * top_middle) = Vec2(0.125, -0.5 + 1e-15);  // just above it: still valid
  EXPECT_FALSE(find_self_intersection(boundary, x, grid, scratch));
  x = rest;
  // Node 5 (-0.25, -0.5) moved past node 0 along the bottom line: its edges 0-5 and 5-10
  // fold flat onto each other.
  x.segment<2>(2 * bottom_second) = Vec2(-0.6, -0.5);
  EXPECT_TRUE(find_self_intersection(boundary, x, grid, scratch));

  const test::TwoSquares two = test::two_squares(0.5, 3, Vec2(0.2, -0.49));  // 1 cm overlap
  EXPECT_TRUE(
      find_self_intersection(two.boundary, test::flat_positions(two.mesh.rest), grid, scratch));
}

TEST(IntersectionCheck, MinimumGapOverPairs) {
  const Mesh mesh = square_mesh(1.0, 4);
  const Boundary boundary = find_boundary(mesh);
  std::vector<PointEdgePair> pairs;
  for (int n = 0; n < boundary.node_count(); ++n)
    for (int e = 0; e < boundary.edge_count(); ++e) {
      const auto& edge = boundary.edges[e];
      if (edge[0] != boundary.nodes[n] && edge[1] != boundary.nodes[n]) pairs.push_back({n, e});
    }
  EXPECT_DOUBLE_EQ(min_self_gap(boundary, pairs, test::flat_positions(mesh.rest)), 0.25);
  EXPECT_EQ(min_self_gap(boundary, {}, test::flat_positions(mesh.rest)), INFINITY);
}

}  // namespace
}  // namespace invfree
