// Self-contact's clearance certificate (potential/self_contact_clearance.h): it holds under
// translation, it is tight (the worst motion, a node and an edge pushed straight at each
// other, brings a pair to its dhat exactly as the certificate runs out), and it is sound:
// wherever it says "clear", a brute-force check of every node-edge pair finds none within
// its dhat, and the approach of two bodies is caught before they are within dhat.
#include "potential/self_contact_clearance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "collision/intersection_check.h"
#include "tests/scene/body_fixtures.h"

namespace invfree {
namespace {

struct Square {
  Mesh mesh;
  Boundary boundary;
  VecX x;
};

Square square(int n_seg) {
  Square s;
  s.mesh = square_mesh(1.0, n_seg);
  s.boundary = find_boundary(s.mesh);
  s.x = test::flat_positions(s.mesh.rest);
  return s;
}

// The smallest distance - dhat_pair over every pair (edge not incident to the node).
double brute_force_slack(const Boundary& b, const std::vector<Vec2>& rest, const VecX& x,
                         double dhat) {
  double slack = INFINITY;
  for (int n = 0; n < b.node_count(); ++n)
    for (int e = 0; e < b.edge_count(); ++e) {
      const int i = b.nodes[n];
      const auto& edge = b.edges[e];
      if (edge[0] == i || edge[1] == i) continue;
      const double d = std::sqrt(point_edge_distance_squared(
          x.segment<2>(2 * i), x.segment<2>(2 * edge[0]), x.segment<2>(2 * edge[1])));
      const bool same = b.node_body[n] == b.edge_body[e];
      const double rest_d =
          std::sqrt(point_edge_distance_squared(rest[i], rest[edge[0]], rest[edge[1]]));
      slack = std::min(slack, d - pair_dhat(dhat, same ? rest_d : 0.0, same));
    }
  return slack;
}

SelfContactClearance measured(const Boundary& b, const std::vector<Vec2>& rest, const VecX& x,
                              double dhat) {
  SelfContactClearance c;
  BroadPhaseGrid grid;
  measure_clearance(b, rest, x, {dhat, 1e5}, grid, c);
  return c;
}

TEST(SelfContactClearance, MeasuresTheSmallestSlackOfAnyPair) {
  for (int n_seg : {1, 4, 16, 64})
    for (double dhat : {0.01, 0.1}) {
      Square s = square(n_seg);
      const SelfContactClearance c = measured(s.boundary, s.mesh.rest, s.x, dhat);
      EXPECT_EQ(c.pairs.size(), c.pair_slack.size());
      // Within the reach every pair is measured; beyond it the bound is reach - dhat.
      EXPECT_LE(c.slack, brute_force_slack(s.boundary, s.mesh.rest, s.x, dhat) + 1e-15) << n_seg;
      EXPECT_GT(c.slack, 0.0) << n_seg;
      EXPECT_EQ(c.dhat, dhat);
    }
}

TEST(SelfContactClearance, ATranslationIsNoMotion) {
  Square s = square(8);
  SelfContactClearance c = measured(s.boundary, s.mesh.rest, s.x, 0.01);
  VecX moved = s.x;
  for (int i = 0; i < s.mesh.node_count(); ++i) moved.segment<2>(2 * i) += Vec2(3.25, -40.5);
  EXPECT_LT(clearance_motion(s.boundary, c, moved, nullptr, 0.0), 1e-12);
  EXPECT_TRUE(is_clear(c, 0.01, clearance_motion(s.boundary, c, moved, nullptr, 0.0)));
  EXPECT_FALSE(is_clear(c, 0.02, 0.0)) << "measured with another dhat";
  // Along a path, the motion is the farthest of its ends.
  VecX p = VecX::Zero(s.x.size());
  p[0] = 0.3;
  EXPECT_NEAR(clearance_motion(s.boundary, c, s.x, &p, 0.5), 0.075, 1e-12);
  SelfContactClearance none;
  EXPECT_EQ(clearance_motion(s.boundary, none, s.x, nullptr, 0.0), INFINITY);
}

// Two bodies 5 cm apart (their closest pairs are the tightest) moved at each other by m
// each: those pairs' slack falls by exactly 2 m, as the certificate assumes, so it is tight.
TEST(SelfContactClearance, IsTightForTwoBodiesMovingAtEachOther) {
  const double dhat = 0.01, gap = 0.05;
  test::TwoSquares two = test::two_squares(0.5, 6, Vec2(0.5 + gap, 0.0));
  const VecX start = test::flat_positions(two.mesh.rest);
  SelfContactClearance c = measured(two.boundary, two.mesh.rest, start, dhat);
  EXPECT_NEAR(c.slack, gap - dhat, 1e-12);
  for (double fraction : {0.5, 0.999999}) {
    const double m = 0.5 * fraction * c.slack;
    VecX z = start;
    for (int i = 0; i < two.mesh.node_count(); ++i) z[2 * i] += i < two.second ? m : -m;
    const double motion = clearance_motion(two.boundary, c, z, nullptr, 0.0);
    EXPECT_NEAR(motion, m, 1e-12);
    EXPECT_TRUE(is_clear(c, dhat, motion));
    EXPECT_NEAR(brute_force_slack(two.boundary, two.mesh.rest, z, dhat), c.slack - 2.0 * m, 1e-12);
  }
  VecX z = start;  // just past: refused
  const double m = 0.5 * c.slack * 1.000001;
  for (int i = 0; i < two.mesh.node_count(); ++i) z[2 * i] += i < two.second ? m : -m;
  EXPECT_FALSE(is_clear(c, dhat, clearance_motion(two.boundary, c, z, nullptr, 0.0)));
}

// Every pair (edge not incident to the node) within its dhat at w: (slot, edge), sorted.
std::vector<PointEdgePair> pairs_within_dhat(const Boundary& b, const std::vector<Vec2>& rest,
                                             const VecX& w, double dhat) {
  std::vector<PointEdgePair> out;
  for (int n = 0; n < b.node_count(); ++n)
    for (int e = 0; e < b.edge_count(); ++e) {
      const int i = b.nodes[n];
      const auto& edge = b.edges[e];
      if (edge[0] == i || edge[1] == i) continue;
      const double d = std::sqrt(point_edge_distance_squared(
          w.segment<2>(2 * i), w.segment<2>(2 * edge[0]), w.segment<2>(2 * edge[1])));
      const bool same = b.node_body[n] == b.edge_body[e];
      const double rest_d =
          std::sqrt(point_edge_distance_squared(rest[i], rest[edge[0]], rest[edge[1]]));
      if (d <= pair_dhat(dhat, same ? rest_d : 0.0, same)) out.push_back({n, e});
    }
  return out;
}

// Random motions of a deformed square, around the certificate's limits: where it says
// "clear", no pair is within its dhat anywhere on the motion (brute force over every pair,
// at points of the path and of the nodes' path boxes) and the boundary does not cross
// itself; where it names near pairs, every pair within its dhat is among them.
TEST(SelfContactClearance, RandomMotionsItCallsClearHaveNoPairWithinDhat) {
  std::mt19937_64 rng(30);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int clear = 0, near = 0, refused = 0, near_found = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Square s = square(trial % 3 == 0 ? 3 : 12);
    const double dhat = trial % 2 ? 0.01 : 0.05;
    // A deformed start: a shear and a bulge, still far from self-contact.
    for (int i = 0; i < s.mesh.node_count(); ++i) {
      const Vec2 r = s.mesh.rest[i];
      s.x.segment<2>(2 * i) = Vec2(r.x() + 0.2 * r.y(), r.y() * (0.7 + 0.3 * r.x() * r.x()));
    }
    SelfContactClearance c = measured(s.boundary, s.mesh.rest, s.x, dhat);
    ASSERT_GT(c.slack, 0.0);
    // Random displacements of a size around the certificate's limits (up to past the
    // nearest pairs' slack), a random translation, and a random path from there.
    const double size = c.slack * (0.05 + 1.5 * std::abs(unit(rng)));
    VecX z = s.x, p(s.x.size());
    const Vec2 shift(5.0 * unit(rng), 5.0 * unit(rng));
    for (int i = 0; i < s.mesh.node_count(); ++i) {
      z.segment<2>(2 * i) += shift + size * Vec2(unit(rng), unit(rng));
      p.segment<2>(2 * i) = size * Vec2(unit(rng), unit(rng));
    }
    const double alpha = std::abs(unit(rng));
    const double m = clearance_motion(s.boundary, c, z, &p, alpha);
    std::vector<PointEdgePair> listed;
    const bool is_clear_here = is_clear(c, dhat, m);
    if (!is_clear_here && !near_pairs(s.boundary, c, dhat, m, listed)) {
      ++refused;
      continue;
    }
    ++(is_clear_here ? clear : near);
    for (int k = 0; k <= 8; ++k) {
      VecX w = z + (alpha * k / 8.0) * p;
      if (k % 2)  // a corner of each node's path box instead
        for (int i = 0; i < s.mesh.node_count(); ++i)
          if (rng() % 2) w[2 * i] = z[2 * i] + alpha * p[2 * i] * double(rng() % 2);
      for (const PointEdgePair& q : pairs_within_dhat(s.boundary, s.mesh.rest, w, dhat)) {
        ++near_found;
        EXPECT_FALSE(is_clear_here) << trial << ": a pair within dhat where it is clear";
        EXPECT_TRUE(std::binary_search(listed.begin(), listed.end(), q))
            << trial << ": node slot " << q.node << ", edge " << q.edge << " not listed";
      }
      if (listed.empty()) {
        BroadPhaseGrid grid;
        std::vector<std::array<int, 2>> scratch;
        EXPECT_FALSE(find_self_intersection(s.boundary, w, grid, scratch)) << trial;
      }
    }
  }
  EXPECT_GT(clear, 50);
  EXPECT_GT(near, 50);
  EXPECT_GT(refused, 20);
  EXPECT_GT(near_found, 0) << "no motion brought a pair within dhat: the test proves little";
}

TEST(SelfContactClearance, TwoBodiesApproachingAreCaughtBeforeDhat) {
  const double dhat = 0.01;
  test::TwoSquares two = test::two_squares(0.5, 6, Vec2(1.5, 0.0));  // 1 m apart
  const VecX start = test::flat_positions(two.mesh.rest);
  SelfContactClearance c = measured(two.boundary, two.mesh.rest, start, dhat);
  ASSERT_GT(c.slack, 0.0);
  bool refused = false;
  for (double gap = 1.0; gap > 0.0; gap -= 0.001) {
    VecX z = start;
    for (int i = two.second; i < two.mesh.node_count(); ++i) z[2 * i] -= 1.0 - gap;
    const double m = clearance_motion(two.boundary, c, z, nullptr, 0.0);
    if (!is_clear(c, dhat, m)) {
      refused = true;
      EXPECT_GT(gap, dhat) << "refused only once the bodies were within dhat";
      break;
    }
    EXPECT_GT(brute_force_slack(two.boundary, two.mesh.rest, z, dhat), 0.0) << gap;
  }
  EXPECT_TRUE(refused);
}

}  // namespace
}  // namespace invfree
