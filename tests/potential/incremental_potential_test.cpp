// The whole incremental potential (inertia, gravity, elasticity, ground barrier, lagged
// friction, ceiling barrier and penalty) against finite differences, with contacts
// active, friction in both its smoothed and its sliding regime.
#include "potential/incremental_potential.h"

#include <gtest/gtest.h>

#include <random>

#include "tests/potential/problem_fixture.h"
#include "tests/test_support.h"

namespace invfree {
namespace {

struct Fixture {
  Mesh mesh = square_mesh(1.0, 3);
  std::vector<double> mass = node_masses(mesh, 1000.0, MassMode::Uniform);
  StepProblem p;
  StepCaches caches;
  SparseHessian hess = build_sparse_hessian(mesh, true);
  VecX z;

  explicit Fixture(Model model, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const int n = mesh.node_count();
    // A large step keeps eps_u = eps_v h well above the FD step.
    test::set_common_terms(p, mesh, mass, model, 0.5, -0.5 - 0.005);
    p.friction.on = true;
    p.friction.eps_u = 1e-3 * p.h;
    p.friction.weight.assign(n, 0.0);
    p.ceiling.on = true;
    p.ceiling_penalty.on = true;
    p.ceiling_penalty.target = 0.5 + 0.002;
    p.ceiling_penalty.stiffness = 1000.0 * mass[0];
    z.resize(2 * n + 1);
    p.x_tilde.resize(2 * n);
    p.x_start.resize(2 * n);
    for (int i = 0; i < n; ++i) {
      z.segment<2>(2 * i) = mesh.rest[i] + 0.02 * Vec2(u(rng), u(rng));
      // Keep boundary rows inside the barrier band, never through a plane.
      if (std::abs(mesh.rest[i].y() + 0.5) < 1e-12)
        z[2 * i + 1] = p.ground.y0 + 0.002 + 0.006 * (u(rng) + 1) / 2;
      if (std::abs(mesh.rest[i].y() - 0.5) < 1e-12)
        z[2 * i + 1] = 0.5 + 0.006 - 0.002 - 0.006 * (u(rng) + 1) / 2;
      p.x_tilde.segment<2>(2 * i) = mesh.rest[i] + 0.05 * Vec2(u(rng), u(rng));
      // Friction displacement: half the nodes inside eps_u (smoothed), half beyond (sliding).
      p.x_start.segment<2>(2 * i) = z.segment<2>(2 * i);
      p.x_start[2 * i] -= (i % 2 ? 0.4 : 3.0) * p.friction.eps_u * (u(rng) > 0 ? 1 : -1);
      p.friction.weight[i] = 50.0 * (u(rng) + 1.5);
    }
    z[2 * n] = 0.5 + 0.006;
  }
};

TEST(IncrementalPotential, GradientAndHessianMatchFiniteDifferences) {
  for (Model model : {Model::NeoHookean, Model::StableNeoHookean, Model::Linear}) {
    for (unsigned seed = 1; seed <= 5; ++seed) {
      Fixture f(model, seed);
      VecX g;
      ip_gradient_hessian(f.p, f.caches, f.z, g, f.hess);
      const double eps = 1e-7;
      const std::function<double(const VecX&)> energy = [&](const VecX& z) {
        return ip_energy(f.p, f.caches, z);
      };
      const VecX fd = test::fd_gradient(energy, f.z, eps);
      EXPECT_LT(test::relative_error(g, fd), 1e-6) << model_name(model) << " seed " << seed;

      Eigen::MatrixXd fdh(f.z.size(), f.z.size());
      SparseHessian scratch = build_sparse_hessian(f.mesh, true);
      for (int k = 0; k < f.z.size(); ++k) {
        VecX a = f.z, b = f.z, ga, gb;
        a[k] += eps;
        b[k] -= eps;
        ip_gradient_hessian(f.p, f.caches, a, ga, scratch);
        ip_gradient_hessian(f.p, f.caches, b, gb, scratch);
        fdh.col(k) = (ga - gb) / (2 * eps);
      }
      const Eigen::MatrixXd h = Eigen::MatrixXd(f.hess.matrix);
      EXPECT_LT(test::relative_error(h, fdh), 1e-6) << model_name(model) << " seed " << seed;
    }
  }
}

TEST(IncrementalPotential, InfiniteOutsideTheFeasibleSet) {
  Fixture f(Model::NeoHookean, 1);
  EXPECT_TRUE(std::isfinite(ip_energy(f.p, f.caches, f.z)));
  VecX below = f.z;
  below[1] = f.p.ground.y0 - 1e-6;  // node 0 is on the bottom row
  EXPECT_TRUE(std::isinf(ip_energy(f.p, f.caches, below)));
  VecX above = f.z;
  above[2 * 3 + 1] = f.z[f.z.size() - 1] + 1e-6;  // node 3 is on the top row
  EXPECT_TRUE(std::isinf(ip_energy(f.p, f.caches, above)));
  VecX inverted = f.z;
  inverted.segment<2>(2 * 5).swap(inverted.segment<2>(2 * 10));  // swap two interior nodes
  EXPECT_TRUE(std::isinf(ip_energy(f.p, f.caches, inverted)));
}

TEST(IncrementalPotential, FixedCeilingIsEliminated) {
  Fixture f(Model::NeoHookean, 2);
  f.p.ceiling_penalty.fixed = true;
  VecX g;
  ip_gradient_hessian(f.p, f.caches, f.z, g, f.hess);
  const int c = static_cast<int>(f.z.size()) - 1;
  EXPECT_EQ(g[c], 0.0);
  const Eigen::MatrixXd h = Eigen::MatrixXd(f.hess.matrix);
  for (int k = 0; k < c; ++k) {
    EXPECT_EQ(h(k, c), 0.0);
    EXPECT_EQ(h(c, k), 0.0);
  }
  EXPECT_EQ(h(c, c), 1.0);
}

}  // namespace
}  // namespace invfree
