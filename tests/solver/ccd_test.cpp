// Additive CCD never misses: every returned time t is checked against a certificate that
// the moving point and segment do not touch on [0, t] (bisection with the distance's
// Lipschitz bound, which proves a positive lower bound on each piece), over random motions
// and near-degenerate ones (grazing, sliding along the edge's line, a shrinking edge,
// hitting an end exactly), and the distance at t is positive. On a mesh: the step bound of
// all pairs leaves every swept pair certified and the end state passes the exact
// intersection check.
#include "solver/ccd.h"

#include <gtest/gtest.h>

#include <random>

#include "collision/broad_phase.h"
#include "collision/intersection_check.h"
#include "potential/point_edge_distance.h"
#include "tests/scene/body_fixtures.h"

namespace invfree {
namespace {

struct Motion {
  Vec2 p, a, b, dp, da, db;
  double distance(double t) const {
    return std::sqrt(point_edge_distance_squared(p + t * dp, a + t * da, b + t * db));
  }
  // |d/dt distance| <= |dp| + max(|da|, |db|): the segment's points move at convex
  // combinations of its ends' velocities.
  double lipschitz() const { return dp.norm() + std::max(da.norm(), db.norm()); }
};

// True when the distance is proved positive on [t0, t1]: on a piece, the distance is at least
// (d(t0) + d(t1) - L (t1 - t0)) / 2; pieces where that is not positive are halved.
bool certified_apart(const Motion& m, double t0, double t1, int depth = 0) {
  const double d0 = m.distance(t0), d1 = m.distance(t1);
  if (!(d0 > 0.0) || !(d1 > 0.0)) return false;
  if (d0 + d1 - m.lipschitz() * (t1 - t0) > 0.0) return true;
  if (depth > 80) return false;
  const double mid = 0.5 * (t0 + t1);
  return certified_apart(m, t0, mid, depth + 1) && certified_apart(m, mid, t1, depth + 1);
}

std::vector<Motion> motions(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  const auto v = [&](double s) { return Vec2(s * u(rng), s * u(rng)); };
  std::vector<Motion> out;
  for (int k = 0; k < count; ++k) {
    Motion m{v(1), v(1), v(1), v(2), v(2), v(2)};
    switch (k % 8) {
      case 1: {  // head-on at the edge's interior, contact at t* in (0, 1)
        m.a = Vec2(-1, 0);
        m.b = Vec2(1, 0);
        m.p = Vec2(0.9 * u(rng), 0.01 + unit(rng));
        m.da = m.db = Vec2::Zero();
        m.dp = Vec2(0.0, -m.p.y() / (0.05 + 0.9 * unit(rng)));
        break;
      }
      case 2:  // grazing: passes the end a at 1e-9 .. 1e-12
        m.dp = Vec2(2.0, 0.0);
        m.da = m.db = Vec2::Zero();
        m.a = Vec2(0.0, std::pow(10.0, -9.0 - 3.0 * unit(rng)));
        m.b = Vec2(0.0, 1.0);
        m.p = Vec2(-1.0, 0.0);
        break;
      case 3:  // sliding along the edge's line towards the end a
        m.a = Vec2(0, 0);
        m.b = Vec2(1, 1);
        m.p = Vec2(-0.5, -0.5) * (1.0 + unit(rng));
        m.dp = Vec2(1.0, 1.0) * (2.0 * unit(rng));
        m.da = m.db = Vec2::Zero();
        break;
      case 4:  // the edge shrinks to a point beside the point
        m.a = Vec2(-1, 0);
        m.b = Vec2(1, 0);
        m.p = Vec2(0.3 * u(rng), 0.1 * unit(rng) + 1e-6);
        m.da = Vec2(1, 0);
        m.db = Vec2(-1, 0);
        m.dp = Vec2(0.0, -0.2 * unit(rng));
        break;
      case 5:  // hits the end b exactly, moving along the edge's normal
        m.a = Vec2(0, 0);
        m.b = Vec2(1, 0);
        m.p = Vec2(1, 0.5);
        m.dp = Vec2(0, -1);
        m.da = m.db = Vec2::Zero();
        break;
      case 6:  // common motion only: the distance never changes
        m.da = m.db = m.dp;
        break;
      case 7:  // tiny start distance, fast
        m.a = Vec2(-1, 0);
        m.b = Vec2(1, 0);
        m.p = Vec2(0.5 * u(rng), 1e-9 * (1.0 + unit(rng)));
        break;
      default:
        break;
    }
    out.push_back(m);
  }
  return out;
}

TEST(Ccd, NeverMissesAContact) {
  int stopped = 0;
  for (const Motion& m : motions(40000, 9)) {
    if (!(m.distance(0.0) > 0.0)) continue;
    const double t = point_edge_ccd(m.p, m.a, m.b, m.dp, m.da, m.db, 1.0);
    ASSERT_GE(t, 0.0);
    ASSERT_LE(t, 1.0);
    EXPECT_GT(m.distance(t), 0.0);
    EXPECT_TRUE(certified_apart(m, 0.0, t))
        << "p " << m.p.transpose() << " a " << m.a.transpose() << " b " << m.b.transpose() << " dp "
        << m.dp.transpose() << " da " << m.da.transpose() << " db " << m.db.transpose() << " t "
        << t;
    stopped += t < 1.0;
  }
  EXPECT_GT(stopped, 10000);  // many trials do collide within the step
}

TEST(Ccd, StopsCloseBeforeAHeadOnContact) {
  // Head-on towards a fixed edge: contact at t*. Additive CCD stops where the distance would
  // next fall below a tenth of the start's: at 0.9 t* (to rounding), not far short of it.
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  for (int k = 0; k < 1000; ++k) {
    const double d0 = 0.01 + unit(rng), contact = 0.05 + 0.9 * unit(rng);
    const Vec2 p(0.9 * u(rng), d0), a(-1, 0), b(1, 0);
    const double t =
        point_edge_ccd(p, a, b, Vec2(0.0, -d0 / contact), Vec2::Zero(), Vec2::Zero(), 1.0);
    EXPECT_GE(t, 0.85 * contact);
    EXPECT_LT(t, contact);
  }
}

TEST(Ccd, IsZeroOnlyWhenAlreadyTouching) {
  const Vec2 a(0, 0), b(1, 0);
  EXPECT_EQ(point_edge_ccd(Vec2(0.5, 0.0), a, b, Vec2(0, 1), Vec2::Zero(), Vec2::Zero(), 1.0), 0.0);
  EXPECT_EQ(point_edge_ccd(Vec2(0.5, 1.0), a, b, Vec2(1, 0), Vec2(1, 0), Vec2(1, 0), 1.0), 1.0);
  EXPECT_EQ(point_edge_ccd(Vec2(0.5, 1.0), a, b, Vec2(0, 0.5), Vec2::Zero(), Vec2::Zero(), 1.0),
            1.0);
}

TEST(Ccd, MeshStepKeepsEveryPairApart) {
  // Two 4x4 squares 2 cm apart, slightly jittered, moved along large random directions.
  const test::TwoSquares two = test::two_squares(0.4, 4, Vec2(0.05, -0.42));
  const Boundary& boundary = two.boundary;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BroadPhaseGrid grid;
  std::vector<PointEdgePair> pairs;
  std::vector<std::array<int, 2>> scratch;
  int limited = 0;
  for (int trial = 0; trial < 300; ++trial) {
    VecX x = test::flat_positions(two.mesh.rest);
    for (int i = 0; i < x.size(); ++i) x[i] += 0.004 * u(rng);
    ASSERT_FALSE(find_self_intersection(boundary, x, grid, scratch));
    VecX p(x.size());
    for (int i = 0; i < p.size(); ++i) p[i] = 0.3 * u(rng);
    swept_point_edge_candidates(boundary, x, p, 1.0, 0.0, grid, pairs);
    const double alpha = self_contact_step(boundary, pairs, x, p, 1.0);
    ASSERT_GT(alpha, 0.0);
    limited += alpha < 1.0;
    for (int n = 0; n < boundary.node_count(); ++n)
      for (int e = 0; e < boundary.edge_count(); ++e) {
        const int i = boundary.nodes[n];
        const auto& edge = boundary.edges[e];
        if (edge[0] == i || edge[1] == i) continue;
        const Motion m{x.segment<2>(2 * i),
                       x.segment<2>(2 * edge[0]),
                       x.segment<2>(2 * edge[1]),
                       alpha * p.segment<2>(2 * i),
                       alpha * p.segment<2>(2 * edge[0]),
                       alpha * p.segment<2>(2 * edge[1])};
        ASSERT_TRUE(certified_apart(m, 0.0, 1.0)) << "trial " << trial;
      }
    const VecX end = x + alpha * p;
    EXPECT_FALSE(find_self_intersection(boundary, end, grid, scratch)) << "trial " << trial;
  }
  EXPECT_GT(limited, 100);  // the directions do fold the boundary
}

}  // namespace
}  // namespace invfree
