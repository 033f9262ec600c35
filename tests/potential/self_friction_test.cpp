// Lagged point-edge friction: what is frozen at the step start (normal force from the
// barrier, closest point, tangent), the tutorial's formula, and gradient and Hessian against
// central differences in the smoothed (|u| < eps_u) and sliding regimes, for closest points
// inside the edge and at either end.
#include "potential/self_friction.h"

#include <gtest/gtest.h>

#include "tests/potential/point_edge_samples.h"
#include "tests/test_support.h"

namespace invfree {
namespace {

constexpr double kDhat = 0.01, kKappa = 1e5, kMu = 0.4;

// One boundary edge (nodes 1 -> 2 of a bare three-node "mesh") and one node 0 against it.
struct OnePair {
  Boundary boundary;
  std::vector<Vec2> rest;
  std::vector<PointEdgePair> pairs{{0, 0}};
  OnePair() {
    boundary.edges = {{1, 2}};
    boundary.edge_body = {1};
    boundary.nodes = {0, 1, 2};
    boundary.node_body = {0, 1, 1};
    boundary.node_area = {0.2, 0.2, 0.2};
    boundary.node_slot = {0, 1, 2};
    rest = {Vec2(0, 1), Vec2(-1, 0), Vec2(1, 0)};
  }
};

VecX positions(const Vec2& p, const Vec2& a, const Vec2& b) {
  VecX x(6);
  x << p, a, b;
  return x;
}

TEST(SelfFriction, LagsNormalForceClosestPointAndTangent) {
  const OnePair one;
  const SelfContactParams params{kDhat, kKappa};
  std::vector<SelfFrictionPair> lagged;
  // Inside the edge: r = 0.3 of the way, normal +y.
  const Vec2 a(-1, 0), b(1, 0);
  VecX x = positions(Vec2(-0.4, 0.004), a, b);
  lag_self_friction(one.boundary, one.rest, one.pairs, x, params, kMu, lagged);
  ASSERT_EQ(lagged.size(), 1u);
  EXPECT_NEAR(lagged[0].r, 0.3, 1e-15);
  EXPECT_NEAR(std::abs(lagged[0].tangent.x()), 1.0, 1e-15);
  EXPECT_NEAR(lagged[0].tangent.y(), 0.0, 1e-12);  // the closest point's rounding
  // weight = mu lambda, lambda = -dB/dd: central difference along the normal.
  const BarrierParams barrier = squared_distance_barrier(kDhat, kKappa, 0.2);
  const double eps = 1e-8;
  const double dbdd = (point_edge_barrier(Vec2(-0.4, 0.004 + eps), a, b, barrier) -
                       point_edge_barrier(Vec2(-0.4, 0.004 - eps), a, b, barrier)) /
                      (2 * eps);
  EXPECT_NEAR(lagged[0].weight, -kMu * dbdd, 1e-6 * std::abs(kMu * dbdd));
  EXPECT_GT(lagged[0].weight, 0.0);
  // Beyond the second end: r = 1, tangent perpendicular to p - b.
  x = positions(Vec2(1.003, 0.004), a, b);
  lag_self_friction(one.boundary, one.rest, one.pairs, x, params, kMu, lagged);
  ASSERT_EQ(lagged.size(), 1u);
  EXPECT_EQ(lagged[0].r, 1.0);
  EXPECT_NEAR(lagged[0].tangent.dot(Vec2(0.003, 0.004)), 0.0, 1e-15);
  // Not within dhat, or no friction coefficient: no pair.
  x = positions(Vec2(0.0, kDhat), a, b);
  lag_self_friction(one.boundary, one.rest, one.pairs, x, params, kMu, lagged);
  EXPECT_TRUE(lagged.empty());
  x = positions(Vec2(0.0, 0.001), a, b);
  lag_self_friction(one.boundary, one.rest, one.pairs, x, params, 0.0, lagged);
  EXPECT_TRUE(lagged.empty());
}

TEST(SelfFriction, IsTheTutorialsFormula) {
  // 8_self_friction/FrictionEnergy.py on velocities v = (x - x^n) / h:
  //   rel_v = v_p - ((1 - r) v_a + r v_b),  vbar = T^T rel_v,  T = I - n n^T,
  //   mu_lam * f0(|vbar|, epsv, h),  f0 = |vbar| h beyond epsv, else
  //   (|vbar| h)^2 (-(|vbar| h)/3 + epsv h) / (epsv h)^2 + epsv h / 3.
  const double h = 0.01, epsv = kFrictionEpsV;
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const double angle = 3.14159 * u(rng);
    const Vec2 n(std::cos(angle), std::sin(angle));
    const SelfFrictionPair f{{0, 1, 2}, 3.0 + u(rng), 0.5 + 0.5 * u(rng), Vec2(-n.y(), n.x())};
    Vec6 dx;
    const double scale = (k % 2 ? 0.3 : 3.0) * epsv * h;  // inside, then beyond, the window
    for (int c = 0; c < 6; ++c) dx[c] = scale * u(rng);
    const Vec2 rel_v =
        (dx.segment<2>(0) - (1 - f.r) * dx.segment<2>(2) - f.r * dx.segment<2>(4)) / h;
    const Vec2 vbar = (Mat2::Identity() - n * n.transpose()) * rel_v;
    const double y = vbar.norm() * h, e = epsv * h;
    const double f0 = vbar.norm() >= epsv ? y : y * y * (-y / 3.0 + e) / (e * e) + e / 3.0;
    EXPECT_NEAR(self_friction_value(f, dx, epsv * h), f.weight * f0, 1e-12 * f.weight * e);
  }
}

TEST(SelfFriction, GradientAndHessianMatchFiniteDifferences) {
  const double eps_u = 1e-5;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  int smoothed = 0, sliding = 0;
  for (int k = 0; k < 2000; ++k) {
    const double angle = 3.14159 * u(rng);
    const double r = k % 3 == 0 ? 0.0 : k % 3 == 1 ? 1.0 : unit(rng);
    const SelfFrictionPair f{
        {0, 1, 2}, 10.0 * unit(rng) + 0.1, r, Vec2(std::cos(angle), std::sin(angle))};
    Vec6 dx;
    for (int c = 0; c < 6; ++c) dx[c] = (k % 2 ? 0.3 : 5.0) * eps_u * u(rng);
    const double slip = slip_direction(f).dot(dx);
    const double fd_step = 1e-4 * eps_u;
    // Keep the stencil on one side of the window's edge |u| = eps_u (the Hessian jumps there).
    if (std::abs(std::abs(slip) - eps_u) < 10 * fd_step) continue;
    (std::abs(slip) < eps_u ? smoothed : sliding)++;
    const std::function<double(const Vec6&)> value = [&](const Vec6& d) {
      return self_friction_value(f, d, eps_u);
    };
    const auto grad = [&](const Vec6& d) { return self_friction_gradient(f, d, eps_u); };
    const Vec6 g = grad(dx);
    EXPECT_LE((g - test::fd_gradient(value, dx, fd_step)).norm(), 1e-6 * f.weight);
    const Mat6 h = self_friction_hessian(f, dx, eps_u);
    EXPECT_LE((h - test::fd_jacobian(grad, dx, fd_step)).norm(), 1e-5 * f.weight / eps_u);
    Eigen::SelfAdjointEigenSolver<Mat6> eig(h);
    EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-12 * f.weight / eps_u);
  }
  EXPECT_GT(smoothed, 500);
  EXPECT_GT(sliding, 500);
}

TEST(SelfFriction, SumsScatterEachPairToItsNodes) {
  const double eps_u = 1e-5;
  std::vector<SelfFrictionPair> pairs = {{{0, 1, 2}, 2.0, 0.25, Vec2(1, 0)},
                                         {{3, 2, 1}, 1.0, 1.0, Vec2(0, 1)}};
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  VecX x_start(8), x(8);
  for (int c = 0; c < 8; ++c) {
    x_start[c] = u(rng);
    x[c] = x_start[c] + 2.0 * eps_u * u(rng);
  }
  const std::function<double(const VecX&)> energy = [&](const VecX& y) {
    return self_friction_energy(pairs, y, x_start, eps_u);
  };
  VecX g = VecX::Zero(8);
  std::vector<PointEdgeHessian> hessians;
  add_self_friction_gradient_hessian(pairs, x, x_start, eps_u, 3.0, g, hessians);
  const VecX fd = test::fd_gradient(energy, x, 1e-9);
  EXPECT_LE((g - 3.0 * fd).norm(), 1e-5 * g.norm());
  Eigen::MatrixXd assembled = Eigen::MatrixXd::Zero(8, 8), fdh(8, 8);
  for (const PointEdgeHessian& ph : hessians)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        assembled.block<2, 2>(2 * ph.nodes[i], 2 * ph.nodes[j]) +=
            ph.hessian.block<2, 2>(2 * i, 2 * j);
  for (int c = 0; c < 8; ++c) {
    VecX a = x, b = x, ga = VecX::Zero(8), gb = VecX::Zero(8);
    a[c] += 1e-9;
    b[c] -= 1e-9;
    std::vector<PointEdgeHessian> unused;
    add_self_friction_gradient_hessian(pairs, a, x_start, eps_u, 3.0, ga, unused);
    add_self_friction_gradient_hessian(pairs, b, x_start, eps_u, 3.0, gb, unused);
    fdh.col(c) = (ga - gb) / 2e-9;
  }
  EXPECT_LE((assembled - fdh).norm(), 1e-4 * assembled.norm());
}

}  // namespace
}  // namespace invfree
