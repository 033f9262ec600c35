// Each per-node term of the incremental potential (gravity.h, plane_barrier.h, friction.h,
// pull_spring.h, ceiling_penalty.h) against central finite differences of its own value:
// gradient from the value, Hessian from the gradient, over a sweep of gaps (down to
// 1e-4 dhat, near the barrier's edge dhat) and slips (inside, at and beyond friction's
// window eps_u, on both sides of zero).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "potential/ceiling_penalty.h"
#include "potential/friction.h"
#include "potential/gravity.h"
#include "potential/plane_barrier.h"
#include "potential/pull_spring.h"

namespace invfree {
namespace {

// The node's unknowns (x, y, c) as a vector, and back.
NodeState with(NodeState s, int k, double value) {
  (k == 0 ? s.x : k == 1 ? s.y : s.ceiling) = value;
  return s;
}
double coordinate(const NodeState& s, int k) {
  return k == 0 ? s.x : k == 1 ? s.y : s.ceiling;
}
std::array<double, 3> gradient_of(const NodeDerivatives& d) {
  return {d.gx, d.gy, d.gc};
}

// Checks a term's gradient (scale 1) against central differences of its value, and its
// Hessian diagonal (xx, yy, cc) and (y, c) entry against central differences of its
// gradient. Relative tolerance on the larger of the two numbers (or an absolute floor).
// `gap`: the distance to the term's nearest singularity; the step is a small part of it.
template <class Term>
void expect_derivatives_match(const Term& term, const NodeState& s, double gap, const char* what) {
  NodeDerivatives d;
  term.add_derivatives(s, 1.0, d);
  for (int k = 0; k < 3; ++k) {
    const double step = 1e-4 * gap;
    const double fd = (term.value(with(s, k, coordinate(s, k) + step)) -
                       term.value(with(s, k, coordinate(s, k) - step))) /
                      (2 * step);
    const double g = gradient_of(d)[k];
    EXPECT_NEAR(g, fd, 1e-5 * std::max({1.0, std::abs(g), std::abs(fd)}))
        << what << ": gradient " << k << " at x=" << s.x << " y=" << s.y << " c=" << s.ceiling;
    NodeDerivatives dp, dm;
    term.add_derivatives(with(s, k, coordinate(s, k) + step), 1.0, dp);
    term.add_derivatives(with(s, k, coordinate(s, k) - step), 1.0, dm);
    const double hk = (gradient_of(dp)[k] - gradient_of(dm)[k]) / (2 * step);
    const double h = k == 0 ? d.hxx : k == 1 ? d.hyy : d.hcc;
    EXPECT_NEAR(h, hk, 1e-4 * std::max({1.0, std::abs(h), std::abs(hk)}))
        << what << ": Hessian " << k << k << " at x=" << s.x << " y=" << s.y;
    if (k == 2) {  // d(g_y)/dc: the (y, c) entry
      const double hyc = (dp.gy - dm.gy) / (2 * step);
      EXPECT_NEAR(d.hyc, hyc, 1e-4 * std::max({1.0, std::abs(d.hyc), std::abs(hyc)})) << what;
    }
  }
}

const BarrierParams kBarrier{0.01, 1e5, 0.25};

std::vector<double> gaps() {  // fractions of dhat: deep in the barrier to beyond it
  return {1e-4, 1e-3, 0.01, 0.1, 0.5, 0.9, 0.999, 1.2};
}

TEST(NodeTerms, GravityMatchesFiniteDifferences) {
  Gravity gravity{true, Vec2(0.3, -9.81)};
  for (double y : {-0.7, 0.0, 0.4})
    expect_derivatives_match(gravity, NodeState{0, 0.2, y, 0.7, 0.0, 1.0}, 1.0, "gravity");
}

TEST(NodeTerms, GroundBarrierMatchesFiniteDifferencesAcrossTheBand) {
  GroundBarrier ground{true, -1.0, kBarrier};
  for (double f : gaps()) {
    const double y = -1.0 + f * kBarrier.dhat;
    expect_derivatives_match(ground, NodeState{0, 0.1, y, 1.0, 0.0, 0.0}, f * kBarrier.dhat,
                             "ground");
    NodeDerivatives d;
    ground.add_derivatives(NodeState{0, 0.1, y, 1.0, 0.0, 0.0}, 1.0, d);
    if (f < 1.0) {
      EXPECT_LT(d.gy, 0.0) << "pushes up inside the band";
      EXPECT_GT(d.hyy, 0.0) << "convex";
    } else {
      EXPECT_EQ(d.gy, 0.0) << "no force beyond dhat";
    }
  }
  EXPECT_TRUE(std::isinf(ground.value(NodeState{0, 0.0, -1.0, 1.0, 0.0, 0.0})));
}

TEST(NodeTerms, CeilingBarrierMatchesFiniteDifferencesAndCouplesTheCeiling) {
  CeilingBarrier ceiling{true, kBarrier};
  for (double f : gaps()) {
    const NodeState s{0, 0.0, 0.5 - f * kBarrier.dhat, 1.0, 0.0, 0.5};
    expect_derivatives_match(ceiling, s, f * kBarrier.dhat, "ceiling");
    NodeDerivatives d;
    ceiling.add_derivatives(s, 1.0, d);
    EXPECT_EQ(d.gy, -d.gc) << "equal and opposite on the node and the ceiling";
    EXPECT_EQ(d.hyc, -d.hyy);
  }
}

TEST(NodeTerms, FrictionMatchesFiniteDifferencesInsideAndBeyondItsWindow) {
  GroundFriction friction;
  friction.on = true;
  friction.eps_u = 1e-5;
  friction.weight = {0.0, 42.0};
  for (double u : {-5.0, -1.5, -0.999, -0.3, -1e-3, 1e-3, 0.5, 0.9, 1.01, 3.0}) {
    const NodeState s{1, 0.2 + u * friction.eps_u, 0.0, 1.0, 0.2, 0.0};
    NodeDerivatives d;
    friction.add_derivatives(s, 1.0, d);
    // Central differences need a step well inside the smooth piece the point is on.
    const double step = 1e-4 * friction.eps_u;
    const double fd =
        (friction.value(with(s, 0, s.x + step)) - friction.value(with(s, 0, s.x - step))) /
        (2 * step);
    EXPECT_NEAR(d.gx, fd, 1e-6 * 42.0) << "u/eps_u=" << u;
    NodeDerivatives dp, dm;
    friction.add_derivatives(with(s, 0, s.x + step), 1.0, dp);
    friction.add_derivatives(with(s, 0, s.x - step), 1.0, dm);
    EXPECT_NEAR(d.hxx, (dp.gx - dm.gx) / (2 * step), 1e-3 * 42.0 / friction.eps_u) << u;
    EXPECT_GE(d.hxx, 0.0);
    EXPECT_LE(std::abs(d.gx), 42.0 * (1 + 1e-12)) << "never more than mu lambda";
  }
  NodeDerivatives none;
  friction.add_derivatives(NodeState{0, 1.0, 0.0, 1.0, 0.0, 0.0}, 1.0, none);
  EXPECT_EQ(none.gx, 0.0) << "a node out of contact (weight 0) feels no friction";
}

TEST(NodeTerms, PullSpringAndCeilingPenaltyMatchFiniteDifferences) {
  const PullSpring pull{true, 3, Vec2(0.5, -0.2), 250.0};
  const Vec2 x(0.1, 0.3);
  double gx = 0, gy = 0, hxx = 0, hyy = 0;
  pull.add_derivatives(x, 2.0, gx, gy, hxx, hyy);
  const double e = 1e-6;
  EXPECT_NEAR(gx, (pull.value(x + Vec2(e, 0), 2.0) - pull.value(x - Vec2(e, 0), 2.0)) / (2 * e),
              1e-6);
  EXPECT_NEAR(gy, (pull.value(x + Vec2(0, e), 2.0) - pull.value(x - Vec2(0, e), 2.0)) / (2 * e),
              1e-6);
  EXPECT_EQ(hxx, 500.0);
  EXPECT_EQ(hyy, 500.0);

  const CeilingPenalty penalty{true, 0.4, 3e4, false};
  for (double c : {0.3, 0.4, 0.55})
    EXPECT_NEAR(penalty.gradient(c), (penalty.value(c + e) - penalty.value(c - e)) / (2 * e),
                1e-5 * std::max(1.0, std::abs(penalty.gradient(c))));
}

// A sloped ground (the course's 4_friction): the barrier along the unit normal and the
// friction along the tangent, their gradient and whole 2x2 Hessian (x-y entry included)
// against central differences in x and y.
template <class Term>
void expect_planar_derivatives_match(const Term& term, const NodeState& s, double step,
                                     const char* what) {
  NodeDerivatives d;
  term.add_derivatives(s, 1.0, d);
  const double g[2] = {d.gx, d.gy};
  const double h[2][2] = {{d.hxx, d.hxy}, {d.hxy, d.hyy}};
  for (int k = 0; k < 2; ++k) {
    const double fd = (term.value(with(s, k, coordinate(s, k) + step)) -
                       term.value(with(s, k, coordinate(s, k) - step))) /
                      (2 * step);
    EXPECT_NEAR(g[k], fd, 1e-5 * std::max({1.0, std::abs(g[k]), std::abs(fd)})) << what << k;
    NodeDerivatives dp, dm;
    term.add_derivatives(with(s, k, coordinate(s, k) + step), 1.0, dp);
    term.add_derivatives(with(s, k, coordinate(s, k) - step), 1.0, dm);
    const double col[2] = {(dp.gx - dm.gx) / (2 * step), (dp.gy - dm.gy) / (2 * step)};
    for (int r = 0; r < 2; ++r)
      EXPECT_NEAR(h[r][k], col[r], 1e-4 * std::max({1.0, std::abs(h[r][k]), std::abs(col[r])}))
          << what << ": Hessian " << r << k;
  }
}

TEST(NodeTerms, SlopedGroundBarrierAndFrictionMatchFiniteDifferences) {
  const Vec2 n = Vec2(0.1, 1.0).normalized();
  GroundBarrier ground{true, -1.0, kBarrier, true, n};
  for (double f : gaps()) {  // a node at gap f dhat above the slope, somewhere along it
    const Vec2 p = Vec2(0.3, -1.0 - 0.1 * 0.3 / 1.0) + f * kBarrier.dhat * n;
    NodeState s{0, p.x(), p.y(), 1.0, 0.0, 0.0};
    EXPECT_NEAR(ground.gap(p.x(), p.y()), f * kBarrier.dhat, 1e-12);
    expect_planar_derivatives_match(ground, s, 1e-4 * f * kBarrier.dhat, "sloped ground");
  }
  GroundFriction friction;
  friction.on = true;
  friction.weight = {2.5};
  friction.eps_u = 1e-5;
  friction.sloped = true;
  friction.tangent = Vec2(n.y(), -n.x());
  for (double u : {-3e-5, -1.2e-5, -9e-6, -4e-6, 1e-7, 6e-6, 2e-5}) {  // slips along t
    const Vec2 start(0.2, -0.5), p = start + u * friction.tangent + 1e-3 * n;
    NodeState s{0, p.x(), p.y(), 1.0, start.x(), 0.0, start.y()};
    EXPECT_NEAR(friction.slip(s), u, 1e-15);
    expect_planar_derivatives_match(friction, s, 1e-3 * friction.eps_u, "sloped friction");
  }
}

}  // namespace
}  // namespace invfree
