// The broad phase against brute force: over random jittered and folded boundaries of one and
// two bodies, with and without motion, its pairs are exactly the non-incident pairs whose
// boxes overlap, sorted, and a superset of every pair that comes within the inflation
// distance at any sampled point of the step; at rest, far fewer pairs than all of them.
#include "collision/broad_phase.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "linalg/parallel.h"
#include "potential/point_edge_distance.h"
#include "tests/scene/body_fixtures.h"

namespace invfree {
namespace {

Box path_box(const VecX& x, const VecX& p, double alpha, int i) {
  const Vec2 a = x.segment<2>(2 * i), b = a + alpha * p.segment<2>(2 * i);
  return {a.cwiseMin(b), a.cwiseMax(b)};
}

std::vector<PointEdgePair> brute_force_boxes(const Boundary& boundary, const VecX& x, const VecX& p,
                                             double alpha, double inflation) {
  std::vector<PointEdgePair> out;
  for (int n = 0; n < boundary.node_count(); ++n)
    for (int e = 0; e < boundary.edge_count(); ++e) {
      const int i = boundary.nodes[n];
      const auto& edge = boundary.edges[e];
      if (edge[0] == i || edge[1] == i) continue;
      Box node = path_box(x, p, alpha, i);
      node.lo.array() -= inflation;
      node.hi.array() += inflation;
      const Box a = path_box(x, p, alpha, edge[0]), b = path_box(x, p, alpha, edge[1]);
      const Vec2 lo = a.lo.cwiseMin(b.lo), hi = a.hi.cwiseMax(b.hi);
      if ((node.lo.array() <= hi.array()).all() && (lo.array() <= node.hi.array()).all())
        out.push_back({n, e});
    }
  return out;
}

TEST(BroadPhase, MatchesBruteForceAndFindsEveryClosePair) {
  const test::TwoSquares two = test::two_squares(0.5, 6, Vec2(0.1, -0.53));
  const Mesh& mesh = two.mesh;
  const Boundary& boundary = two.boundary;
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BroadPhaseGrid grid;  // reused across trials, as in a run
  std::vector<PointEdgePair> pairs;
  int close = 0;
  for (int trial = 0; trial < 200; ++trial) {
    VecX x = test::flat_positions(mesh.rest);
    // Jitter, and on odd trials fold the upper body's top onto itself.
    for (int i = 0; i < x.size(); ++i) x[i] += 0.02 * u(rng);
    if (trial % 2)
      for (int i = 0; i < two.second; ++i)
        if (x[2 * i + 1] > 0.1) x[2 * i + 1] = 0.2 - x[2 * i + 1];
    VecX p(x.size());
    const double speed = trial % 3 == 0 ? 0.0 : 0.2;
    for (int i = 0; i < p.size(); ++i) p[i] = speed * u(rng);
    const double inflation = 0.01 * (1 + trial % 4), alpha = trial % 5 ? 1.0 : 0.3;
    if (speed == 0.0)
      point_edge_candidates(boundary, x, inflation, grid, pairs);
    else
      swept_point_edge_candidates(boundary, x, p, alpha, inflation, grid, pairs);
    EXPECT_EQ(pairs, brute_force_boxes(boundary, x, p, speed == 0.0 ? 0.0 : alpha, inflation))
        << "trial " << trial;
    const std::set<PointEdgePair> found(pairs.begin(), pairs.end());
    for (int n = 0; n < boundary.node_count(); ++n)
      for (int e = 0; e < boundary.edge_count(); ++e) {
        const int i = boundary.nodes[n];
        const auto& edge = boundary.edges[e];
        if (edge[0] == i || edge[1] == i) continue;
        for (int s = 0; s <= 10; ++s) {
          const VecX at = x + (speed == 0.0 ? 0.0 : alpha * s / 10.0) * p;
          const double d2 = point_edge_distance_squared(
              at.segment<2>(2 * i), at.segment<2>(2 * edge[0]), at.segment<2>(2 * edge[1]));
          if (d2 < inflation * inflation) {
            ++close;
            EXPECT_TRUE(found.count({n, e})) << "trial " << trial << " node " << n << " edge " << e;
            break;
          }
        }
      }
  }
  EXPECT_GT(close, 1000);
}

TEST(BroadPhase, FindsFewPairsOnAFineMeshAtRest) {
  const Mesh mesh = square_mesh(1.0, 256);
  const Boundary boundary = find_boundary(mesh);
  BroadPhaseGrid grid;
  std::vector<PointEdgePair> pairs;
  const VecX x = test::flat_positions(mesh.rest);
  point_edge_candidates(boundary, x, 0.01, grid, pairs);
  ASSERT_EQ(boundary.edge_count(), 1024);
  EXPECT_EQ(pairs, brute_force_boxes(boundary, x, VecX::Zero(x.size()), 0.0, 0.01));
  // Each node's box reaches about 2.6 edges either way along its side: a few pairs per node
  // out of the 1,024 x 1,022 non-incident ones.
  EXPECT_LT(pairs.size(), 8u * 1024);
}

TEST(BroadPhase, EdgePairsAreTheOverlappingBoxes) {
  const Mesh mesh = square_mesh(1.0, 5);
  const Boundary boundary = find_boundary(mesh);
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BroadPhaseGrid grid;
  std::vector<std::array<int, 2>> pairs;
  for (int trial = 0; trial < 50; ++trial) {
    VecX x = test::flat_positions(mesh.rest);
    for (int i = 0; i < x.size(); ++i) x[i] += 0.3 * u(rng);
    edge_edge_candidates(boundary, x, grid, pairs);
    std::vector<std::array<int, 2>> brute;
    for (int f = 0; f < boundary.edge_count(); ++f)
      for (int e = 0; e < f; ++e) {
        const auto box = [&](int k) {
          const Vec2 a = x.segment<2>(2 * boundary.edges[k][0]),
                     b = x.segment<2>(2 * boundary.edges[k][1]);
          return Box{a.cwiseMin(b), a.cwiseMax(b)};
        };
        const Box be = box(e), bf = box(f);
        if ((be.lo.array() <= bf.hi.array()).all() && (bf.lo.array() <= be.hi.array()).all())
          brute.push_back({e, f});
      }
    std::sort(brute.begin(), brute.end(), [](const auto& l, const auto& r) {
      return l[1] != r[1] ? l[1] < r[1] : l[0] < r[0];
    });
    EXPECT_EQ(pairs, brute);
  }
}

// Blocks of nodes search the grid concurrently (above 256 boundary nodes): the list is the
// brute force's, entry for entry, on 1, 2 and 3 threads, for a folded, moving pair of
// 96-segment squares (768 boundary nodes, six blocks).
TEST(BroadPhase, SameListOnAnyThreadCount) {
  const test::TwoSquares two = test::two_squares(0.5, 96, Vec2(0.1, -0.505));
  VecX x = test::flat_positions(two.mesh.rest);
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < x.size(); ++i) x[i] += 0.003 * u(rng);
  for (int i = 0; i < two.second; ++i)
    if (x[2 * i + 1] > 0.1) x[2 * i + 1] = 0.2 - x[2 * i + 1];
  VecX p(x.size());
  for (int i = 0; i < p.size(); ++i) p[i] = 0.01 * u(rng);
  ASSERT_EQ(two.boundary.node_count(), 768);
  const std::vector<PointEdgePair> expected = brute_force_boxes(two.boundary, x, p, 0.8, 0.01);
  ASSERT_GT(expected.size(), 2000u);
  for (int threads : {1, 2, 3}) {
    set_thread_count(threads);
    BroadPhaseGrid grid;
    reserve_candidates(two.boundary.node_count(), 4, grid);
    std::vector<PointEdgePair> pairs;
    swept_point_edge_candidates(two.boundary, x, p, 0.8, 0.01, grid, pairs);
    EXPECT_EQ(pairs, expected) << threads << " threads";
    point_edge_candidates(two.boundary, x, 0.01, grid, pairs);  // the same grid, reused
    EXPECT_EQ(pairs, brute_force_boxes(two.boundary, x, p, 0.0, 0.01)) << threads << " threads";
  }
  set_thread_count(0);
}

}  // namespace
}  // namespace invfree
