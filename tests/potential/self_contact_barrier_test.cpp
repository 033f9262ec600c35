// The point-edge barrier: the tutorial's formula, its relation to the ground's barrier,
// gradient and Hessian against central differences in every regime and near the switches,
// the PSD projection; and the dhat rule: a body at rest or moved rigidly (n_seg 4..256),
// falling freely (the simulation, n_seg 4..64) or landing and resting on the ground feels
// exactly zero self-contact force, while pairs of a fold or of two bodies within dhat do.
#include "potential/self_contact_barrier.h"

#include <gtest/gtest.h>

#include <random>

#include "collision/broad_phase.h"
#include "linalg/parallel.h"
#include "material/polar_svd.h"
#include "material/psd_projection.h"
#include "simulation.h"
#include "tests/potential/point_edge_samples.h"
#include "tests/scene/body_fixtures.h"
#include "tests/test_support.h"

namespace invfree {
namespace {

constexpr double kDhat = 0.01, kKappa = 1e5;

TEST(SelfContactBarrier, IsTheTutorialsFormula) {
  const double area = 0.225;
  const BarrierParams b = squared_distance_barrier(kDhat, kKappa, area);
  for (double d : {1e-5, 1e-3, 5e-3, 9.99e-3}) {
    const Vec2 a(-1.0, 0.0), e(1.0, 0.0), p(0.3, d);
    const double s = d * d / (kDhat * kDhat);
    // 7_self_contact/BarrierEnergy.py: 0.5 * contact_area * dhat * kappa / 8 * (s - 1) * log(s)
    const double tutorial = 0.5 * area * kDhat * kKappa / 8 * (s - 1) * std::log(s);
    EXPECT_NEAR(point_edge_barrier(p, a, e, b), tutorial, 1e-13 * std::abs(tutorial));
  }
  EXPECT_EQ(point_edge_barrier(Vec2(0.3, kDhat), Vec2(-1, 0), Vec2(1, 0), b), 0.0);
  EXPECT_EQ(point_edge_barrier(Vec2(0.3, 0.0), Vec2(-1, 0), Vec2(1, 0), b), INFINITY);
}

TEST(SelfContactBarrier, CurvatureAtDhatIsHalfTheGrounds) {
  // d^2 B / dd^2 at d -> dhat: the ground's a kappa / dhat, halved (each contact of two facing
  // surfaces is counted from both sides).
  const double area = 0.1, d = kDhat * (1.0 - 1e-9);
  const BarrierParams b = squared_distance_barrier(kDhat, kKappa, area);
  const double d2b =
      barrier_derivative(d * d, b) * 2.0 + barrier_second_derivative(d * d, b) * 4.0 * d * d;
  const double ground = barrier_second_derivative(d, {kDhat, kKappa, area});
  EXPECT_NEAR(d2b, 0.5 * ground, 1e-6 * ground);
}

TEST(SelfContactBarrier, GradientAndHessianMatchFiniteDifferences) {
  int checked = 0;
  for (const test::PointEdgeSample& raw : test::point_edge_samples(5000, 4)) {
    // Scale each configuration so that its distance lies in (0.02, 0.98) dhat.
    const double d = std::sqrt(point_edge_distance_squared(raw.p, raw.a, raw.b));
    if (!(d > 0.0)) continue;
    const double target = kDhat * (0.02 + 0.96 * ((checked * 37) % 100) / 100.0);
    const double k = target / d;
    // Edges up to 1 m, as in a scene (the sweep's long edges with a close point would
    // otherwise become kilometres long, where rounding, not the derivative, is measured).
    if (k * (raw.b - raw.a).norm() > 1.0) continue;
    const Vec2 p = k * raw.p, a = k * raw.a, b = k * raw.b;
    const BarrierParams params = squared_distance_barrier(kDhat, kKappa, 0.05);
    const auto split = [](const Vec6& x) {
      return std::array<Vec2, 3>{x.segment<2>(0), x.segment<2>(2), x.segment<2>(4)};
    };
    const std::function<double(const Vec6&)> value = [&](const Vec6& x) {
      const auto [xp, xa, xb] = split(x);
      return point_edge_barrier(xp, xa, xb, params);
    };
    const auto grad = [&](const Vec6& x) {
      const auto [xp, xa, xb] = split(x);
      return point_edge_barrier_gradient(xp, xa, xb, params);
    };
    Vec6 x;
    x << p, a, b;
    // A step well below both the distance and the edge's length (short edges turn fast).
    const double eps = 1e-5 * std::min(target, (b - a).norm());
    const Vec6 g = grad(x);
    EXPECT_LE((g - test::fd_gradient(value, x, eps)).norm(), 1e-6 * g.norm());
    const PointEdgeRegime r = point_edge_regime(p, a, b);
    bool one_regime = true;
    for (int c = 0; c < 6; ++c)
      for (double s : {-eps, eps}) {
        Vec6 y = x;
        y[c] += s;
        const auto [yp, ya, yb] = split(y);
        one_regime &= point_edge_regime(yp, ya, yb) == r;
      }
    if (!one_regime) continue;
    ++checked;
    const Mat6 h = point_edge_barrier_hessian(p, a, b, params, false);
    EXPECT_LE((h - test::fd_jacobian(grad, x, eps)).norm(), 1e-5 * h.norm());
    const Mat6 projected = point_edge_barrier_hessian(p, a, b, params, true);
    // Closed form (point-point) and the 4x4 reduction (point-line): the same as clamping the
    // eigenvalues of the whole 6x6.
    EXPECT_LE((projected - project_psd<6>(h)).norm(), 1e-10 * h.norm());
    Eigen::SelfAdjointEigenSolver<Mat6> eig(projected);
    EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-12 * h.norm());
    Eigen::SelfAdjointEigenSolver<Mat6> exact(h);
    if (exact.eigenvalues().minCoeff() >= 0.0) {
      EXPECT_EQ(projected, h);
    }
    // The projection keeps the positive part: v^T P v = v^T H v along H's positive
    // eigenvectors.
    const Vec6 top = exact.eigenvectors().col(5);
    EXPECT_NEAR(top.dot(projected * top), top.dot(h * top), 1e-9 * h.norm());
  }
  EXPECT_GT(checked, 2500);
}

TEST(SelfContactBarrier, PairDhatRule) {
  EXPECT_EQ(pair_dhat(0.01, 0.0039, true), 0.5 * 0.0039);
  EXPECT_EQ(pair_dhat(0.01, 0.5, true), 0.01);
  EXPECT_EQ(pair_dhat(0.01, 0.0, false), 0.01);
}

// Energy, gradient and Hessians of the self-contact term over the broad phase's pairs.
struct Evaluation {
  double energy = 0.0;
  VecX gradient;
  std::vector<PointEdgeHessian> hessians;
  int pairs_within_scene_dhat = 0;
};

Evaluation evaluate(const Mesh& mesh, const Boundary& boundary, const VecX& x) {
  BroadPhaseGrid grid;
  std::vector<PointEdgePair> pairs;
  point_edge_candidates(boundary, x, kDhat, grid, pairs);
  Evaluation out;
  const SelfContactParams params{kDhat, kKappa};
  out.energy = self_contact_energy(boundary, mesh.rest, pairs, x, params);
  out.gradient = VecX::Zero(x.size());
  add_self_contact_gradient_hessian(boundary, mesh.rest, pairs, x, params, 1.0, out.gradient,
                                    out.hessians);
  for (const PointEdgePair& pr : pairs) {
    const auto& e = boundary.edges[pr.edge];
    const int i = boundary.nodes[pr.node];
    out.pairs_within_scene_dhat +=
        point_edge_distance_squared(x.segment<2>(2 * i), x.segment<2>(2 * e[0]),
                                    x.segment<2>(2 * e[1])) < kDhat * kDhat;
  }
  return out;
}

void expect_no_force(const Mesh& mesh, const Boundary& boundary, const VecX& x,
                     const std::string& what) {
  const Evaluation e = evaluate(mesh, boundary, x);
  EXPECT_EQ(e.energy, 0.0) << what;
  EXPECT_TRUE(e.gradient.isZero(0.0)) << what;
  EXPECT_TRUE(e.hessians.empty()) << what;
}

TEST(SelfContactBarrier, NoForceAtRestOrMovedRigidly) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n_seg : {4, 8, 16, 32, 64, 128, 256}) {
    const Mesh mesh = square_mesh(1.0, n_seg);
    const Boundary boundary = find_boundary(mesh);
    const VecX rest = test::flat_positions(mesh.rest);
    expect_no_force(mesh, boundary, rest, "rest n_seg " + std::to_string(n_seg));
    // Not vacuous: with the scene's dhat for every pair, a fine mesh would push on itself.
    if (n_seg >= 128) {
      EXPECT_GT(evaluate(mesh, boundary, rest).pairs_within_scene_dhat, 0);
    }
    for (int trial = 0; trial < 3; ++trial) {
      const Mat2 r = rotation(3.14159 * u(rng));
      const Vec2 t(10.0 * u(rng), 10.0 * u(rng));
      std::vector<Vec2> moved;
      for (const Vec2& X : mesh.rest) moved.push_back(r * X + t);
      expect_no_force(mesh, boundary, test::flat_positions(moved),
                      "rigid n_seg " + std::to_string(n_seg));
    }
  }
}

// Runs a scene and checks every state; returns the number of steps taken.
int run_and_check(SceneDef scene, int steps) {
  Simulation sim = make_simulation(scene);
  const Boundary boundary = find_boundary(sim.mesh);
  for (int s = 0; s < steps; ++s) {
    const StepReport report = step(sim);
    if (report.status != StepStatus::Ok) return s;
    expect_no_force(
        sim.mesh, boundary, sim.x,
        scene.name + " n_seg " + std::to_string(scene.n_seg) + " step " + std::to_string(s));
  }
  return steps;
}

TEST(SelfContactBarrier, NoForceFallingFreely) {
  // The simulation's own free fall (implicit Euler, elasticity, gravity, no planes) up to
  // n_seg 64; n_seg 128 and 256 move the same way, a translation, which the rigid-motion
  // test above covers without their ~10 s of setup and steps.
  for (int n_seg : {4, 16, 64}) {
    SceneDef scene;
    scene.name = "free fall";
    scene.n_seg = n_seg;
    scene.has_ground = scene.has_ceiling = false;
    scene.initial_velocity = Vec2(0.7, 2.0);
    ASSERT_EQ(validate_scene(scene), "");
    EXPECT_EQ(run_and_check(scene, 10), 10);
  }
}

TEST(SelfContactBarrier, NoForceLandingAndRestingOnTheGround) {
  // The body falls 0.5 m, lands (compression waves) and settles under gravity, which
  // compresses its lower part: at n_seg 16 and 32, 150 steps (1.5 s).
  for (int n_seg : {16, 32}) {
    SceneDef scene;
    scene.name = "landing";
    scene.n_seg = n_seg;
    scene.has_ceiling = false;
    ASSERT_EQ(validate_scene(scene), "");
    EXPECT_EQ(run_and_check(scene, 150), 150);
  }
}

TEST(SelfContactBarrier, PushesAFoldApartAndTwoBodies) {
  // One body: a top-side node brought to 2 mm above a bottom-side edge (far apart at rest,
  // so the scene's dhat applies) is pushed up, the edge's nodes down.
  const Mesh mesh = square_mesh(1.0, 8);
  const Boundary boundary = find_boundary(mesh);
  VecX x = test::flat_positions(mesh.rest);
  const int top = 4 * 9 + 8;  // node (4, 8): x = 0, y = 0.5
  x.segment<2>(2 * top) = Vec2(0.0625, -0.5 + 0.002);
  const Evaluation fold = evaluate(mesh, boundary, x);
  EXPECT_GT(fold.energy, 0.0);
  EXPECT_LT(fold.gradient[2 * top + 1], 0.0);  // energy falls as the node moves up
  EXPECT_FALSE(fold.hessians.empty());

  // Two bodies 5 mm apart: each body's facing nodes pushed away from the other.
  const test::TwoSquares two = test::two_squares(0.45, 4, Vec2(0.0, -0.45 - 0.005));
  const Evaluation touching = evaluate(two.mesh, two.boundary, test::flat_positions(two.mesh.rest));
  EXPECT_GT(touching.energy, 0.0);
  double push_top = 0.0, push_bottom = 0.0;
  for (int i = 0; i < two.mesh.node_count(); ++i)
    (i < two.second ? push_top : push_bottom) += touching.gradient[2 * i + 1];
  EXPECT_LT(push_top, 0.0);
  EXPECT_GT(push_bottom, 0.0);
}

// The sums over pairs on the threads (a PairSumScratch) against the serial loop: two
// 256-segment squares 5 mm apart, every node jittered by up to 2 mm, give ~11k candidate
// pairs (several blocks of the energy's 1,024 and the derivatives' 256) and a few thousand
// active ones. Energy, gradient and Hessian blocks must have the serial loop's bits on 1,
// 2 and 3 threads: each pair's terms come from its own slots, added in pair order.
TEST(SelfContactBarrier, PairSumsOnTheThreadsHaveTheSerialLoopsBits) {
  const test::TwoSquares two = test::two_squares(1.0, 256, Vec2(0.1, -1.005));
  VecX x = test::flat_positions(two.mesh.rest);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2e-3, 2e-3);
  for (int i = 0; i < x.size(); ++i) x[i] += u(rng);
  BroadPhaseGrid grid;
  std::vector<PointEdgePair> pairs;
  point_edge_candidates(two.boundary, x, kDhat, grid, pairs);
  ASSERT_GE(pairs.size(), 4u * 1024);
  const SelfContactParams params{kDhat, kKappa};
  const double serial_energy = self_contact_energy(two.boundary, two.mesh.rest, pairs, x, params);
  VecX serial_gradient = VecX::Zero(x.size());
  std::vector<PointEdgeHessian> serial_hessians;
  add_self_contact_gradient_hessian(two.boundary, two.mesh.rest, pairs, x, params, 0.7,
                                    serial_gradient, serial_hessians);
  ASSERT_GE(serial_hessians.size(), 1000u);
  ASSERT_GT(serial_energy, 0.0);
  for (int threads : {1, 2, 3}) {
    set_thread_count(threads);
    PairSumScratch scratch;
    const double energy =
        self_contact_energy(two.boundary, two.mesh.rest, pairs, x, params, &scratch);
    VecX gradient = VecX::Zero(x.size());
    std::vector<PointEdgeHessian> hessians;
    add_self_contact_gradient_hessian(two.boundary, two.mesh.rest, pairs, x, params, 0.7, gradient,
                                      hessians, &scratch);
    EXPECT_EQ(energy, serial_energy) << threads << " threads";
    EXPECT_TRUE(gradient == serial_gradient) << threads << " threads";
    ASSERT_EQ(hessians.size(), serial_hessians.size()) << threads << " threads";
    for (size_t k = 0; k < hessians.size(); ++k) {
      EXPECT_EQ(hessians[k].nodes, serial_hessians[k].nodes) << "block " << k;
      EXPECT_TRUE(hessians[k].hessian == serial_hessians[k].hessian) << "block " << k;
    }
  }
  set_thread_count(0);
}

}  // namespace
}  // namespace invfree
