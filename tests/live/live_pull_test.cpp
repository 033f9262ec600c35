// The grab spring the live window adds while a node is dragged (core: StepProblem::pull_*,
// Simulation::pull): h^2 k/2 |x_node - target|^2 in the incremental potential. Its value,
// gradient and Hessian against finite differences (with every other term on), exactly
// the difference it makes when switched on, and what it does to a running simulation.
#include <gtest/gtest.h>

#include <random>

#include "app/live/live_controller.h"
#include "potential/incremental_potential.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"
#include "solver/step_workspace.h"
#include "tests/potential/problem_fixture.h"
#include "tests/test_support.h"

namespace invfree {
namespace {

struct PullFixture {
  Mesh mesh = square_mesh(1.0, 3);
  std::vector<double> mass = node_masses(mesh, 1000.0, MassMode::Uniform);
  StepProblem p;
  StepCaches caches;
  SparseHessian hess = build_sparse_hessian(mesh, false);
  VecX z;

  explicit PullFixture(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const int n = mesh.node_count();
    test::set_common_terms(p, mesh, mass, Model::NeoHookean, 0.05, -0.6);
    z.resize(2 * n);
    p.x_tilde.resize(2 * n);
    p.x_start.resize(2 * n);
    for (int i = 0; i < n; ++i) {
      z.segment<2>(2 * i) = mesh.rest[i] + 0.03 * Vec2(u(rng), u(rng));
      p.x_tilde.segment<2>(2 * i) = mesh.rest[i] + 0.05 * Vec2(u(rng), u(rng));
    }
    p.x_start = z;
    p.pull.on = true;
    p.pull.node = static_cast<int>(seed) % n;
    p.pull.target = Vec2(0.7 * u(rng), 0.9 + 0.3 * u(rng));
    p.pull.stiffness = 2e4 * (1.5 + u(rng));
  }
};

TEST(PullSpring, GradientAndHessianMatchFiniteDifferences) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    PullFixture f(seed);
    VecX g;
    ip_gradient_hessian(f.p, f.caches, f.z, g, f.hess);
    const double eps = 1e-7;
    const std::function<double(const VecX&)> energy = [&](const VecX& z) {
      return ip_energy(f.p, f.caches, z);
    };
    EXPECT_LT(test::relative_error(g, test::fd_gradient(energy, f.z, eps)), 1e-6)
        << "seed " << seed;
    Eigen::MatrixXd fdh(f.z.size(), f.z.size());
    SparseHessian scratch = build_sparse_hessian(f.mesh, false);
    for (int k = 0; k < f.z.size(); ++k) {
      VecX a = f.z, b = f.z, ga, gb;
      a[k] += eps;
      b[k] -= eps;
      ip_gradient_hessian(f.p, f.caches, a, ga, scratch);
      ip_gradient_hessian(f.p, f.caches, b, gb, scratch);
      fdh.col(k) = (ga - gb) / (2 * eps);
    }
    EXPECT_LT(test::relative_error(Eigen::MatrixXd(f.hess.matrix), fdh), 1e-6) << "seed " << seed;
  }
}

TEST(PullSpring, AddsExactlyItsOwnTerm) {
  PullFixture f(3);
  VecX g_on, g_off;
  ip_gradient_hessian(f.p, f.caches, f.z, g_on, f.hess);
  const Eigen::MatrixXd h_on(f.hess.matrix);
  const double e_on = ip_energy(f.p, f.caches, f.z);
  f.p.pull.on = false;
  ip_gradient_hessian(f.p, f.caches, f.z, g_off, f.hess);
  const Eigen::MatrixXd h_off(f.hess.matrix);
  const double e_off = ip_energy(f.p, f.caches, f.z);
  const int i = f.p.pull.node;
  const double k = f.p.h * f.p.h * f.p.pull.stiffness;
  const Vec2 d = f.z.segment<2>(2 * i) - f.p.pull.target;
  EXPECT_NEAR(e_on - e_off, 0.5 * k * d.squaredNorm(), 1e-9 * std::abs(e_on));
  VecX dg = VecX::Zero(g_on.size());
  dg.segment<2>(2 * i) = k * d;
  EXPECT_LT((g_on - g_off - dg).norm(), 1e-9 * g_on.norm());
  Eigen::MatrixXd dh = Eigen::MatrixXd::Zero(h_on.rows(), h_on.cols());
  dh(2 * i, 2 * i) = dh(2 * i + 1, 2 * i + 1) = k;
  EXPECT_LT((h_on - h_off - dh).norm(), 1e-9 * h_on.norm());
}

TEST(PullSpring, PullsANodeOnlyWhileOn) {
  SceneDef s = *load_builtin_scene("drop").scene;
  Simulation pulled = make_simulation(s), free = make_simulation(s);
  const int node = s.n_seg * (s.n_seg + 1) + s.n_seg;  // the top right corner
  const Vec2 start = pulled.x.segment<2>(2 * node);
  pulled.pull = {true, node, start + Vec2(0.5, 1.0), 5e4};
  for (int k = 0; k < 30; ++k) {
    ASSERT_EQ(step(pulled).status, StepStatus::Ok);
    ASSERT_EQ(step(free).status, StepStatus::Ok);
  }
  // Pulled up and right against gravity; the free square fell.
  EXPECT_GT(pulled.x[2 * node + 1], start.y());
  EXPECT_GT(pulled.x[2 * node], start.x() + 0.05);
  EXPECT_LT(free.x[2 * node + 1], start.y());
  for (double d : triangle_det_f(pulled)) EXPECT_GT(d, 0.0);
  // Off again: the same step as without a spring. (Both factorise afresh: a factor reused
  // from the pulled steps would make PCG stop at another iterate, equal only to within
  // Newton's tolerance.)
  pulled.pull.on = false;
  pulled.workspace->newton.solver.invalidate();
  Simulation copy = make_simulation(s);
  copy.x = pulled.x;
  copy.v = pulled.v;
  ASSERT_EQ(step(pulled).status, StepStatus::Ok);
  ASSERT_EQ(step(copy).status, StepStatus::Ok);
  EXPECT_LT((pulled.x - copy.x).norm(), 1e-9);
}

TEST(PullSpring, TheControllerGrabsAndReleases) {
  live::LiveController lc({{"compress", *load_builtin_scene("compress").scene}}, 0);
  const int node = 2;  // bottom row
  const Vec2 start = lc.simulation().x.segment<2>(2 * node);
  lc.begin_pull(node, start + Vec2(-0.6, 0.3));
  EXPECT_TRUE(lc.pulling());
  EXPECT_TRUE(lc.simulation().pull.on);
  for (int k = 0; k < 20; ++k) ASSERT_TRUE(lc.step_once()) << lc.banner;
  EXPECT_LT(lc.simulation().x[2 * node], start.x() - 0.05);
  lc.end_pull();
  EXPECT_FALSE(lc.simulation().pull.on);
  lc.begin_pull(10000, start);  // no such node: ignored
  EXPECT_FALSE(lc.pulling());
}

}  // namespace
}  // namespace invfree
