// Adding a term to the incremental potential touches its own definition and the list, and
// nothing else: a uniform wind (a dead load, -f.x_i per node) defined in this file alone,
// appended to StepProblem's list of node terms, enters every sum written over the list
// (potential/term_sums.h): the energy, the gradient and Hessian (checked against central
// differences of the energy), explicit integration's force and the energy report's bins.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "potential/term_sums.h"
#include "scene/mesh.h"
#include "tests/potential/problem_fixture.h"

namespace invfree {
namespace {

// The term: its own file in the core would hold just this.
struct Wind {
  static constexpr EnergyKind kind = EnergyKind::Load;
  bool on = true;
  Vec2 force = Vec2(3.0, -1.5);  // N per node

  double value(const NodeState& s) const { return -(force.x() * s.x + force.y() * s.y); }
  void add_derivatives(const NodeState&, double scale, NodeDerivatives& d) const {
    d.gx -= scale * force.x();
    d.gy -= scale * force.y();
  }
};
static_assert(NodeTerm<Wind>);

// The list, with the wind appended.
struct WindProblem : StepProblem {
  Wind wind;
  template <class Fn>
  void for_each_node_term(Fn&& fn) const {
    StepProblem::for_each_node_term(fn);
    fn(wind);
  }
};

struct Fixture {
  Mesh mesh = square_mesh(1.0, 4);
  std::vector<double> mass = node_masses(mesh, 1000.0, MassMode::Uniform);
  WindProblem p;
  StepCaches caches;
  VecX z;

  Fixture() {
    test::set_common_terms(p, mesh, mass, Model::NeoHookean, 0.01, -0.6);
    const int n = mesh.node_count();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    z.resize(2 * n);
    p.x_tilde.resize(2 * n);
    p.x_start.resize(2 * n);
    for (int i = 0; i < n; ++i) {
      z.segment<2>(2 * i) = mesh.rest[i] + 0.01 * Vec2(u(rng), u(rng));
      p.x_tilde.segment<2>(2 * i) = mesh.rest[i];
      p.x_start.segment<2>(2 * i) = mesh.rest[i];
    }
  }
  // The sums over the list with the wind on or off.
  double energy(bool wind, const VecX& at) {
    p.wind.on = wind;
    return sum_energy(p, caches, at);
  }
};

double wind_potential(const Fixture& f) {
  double e = 0.0;
  for (int i = 0; i < f.mesh.node_count(); ++i)
    e -= f.p.wind.force.dot(f.z.segment<2>(2 * i));
  return e;
}

TEST(TermList, AnAppendedNodeTermEntersTheEnergyScaledByH2) {
  Fixture f;
  const double h2 = f.p.h * f.p.h;
  const double added = f.energy(true, f.z) - f.energy(false, f.z);
  EXPECT_NEAR(added, h2 * wind_potential(f), 1e-9 * std::abs(f.energy(false, f.z)));
  EXPECT_NE(added, 0.0);
}

TEST(TermList, AnAppendedNodeTermsGradientMatchesItsEnergy) {
  Fixture f;
  SparseHessian hess = build_sparse_hessian(f.mesh, false);
  VecX g(f.z.size());
  Assembly out{g, hess};
  ASSERT_TRUE(assemble_terms(f.p, f.caches, f.z, out));
  const double step = 1e-7;
  for (int k = 0; k < f.z.size(); ++k) {
    VecX a = f.z, b = f.z;
    a[k] += step;
    b[k] -= step;
    const double fd = (f.energy(true, a) - f.energy(true, b)) / (2 * step);
    EXPECT_NEAR(g[k], fd, 1e-6 * std::max(1.0, std::abs(fd))) << "dof " << k;
  }
  // Without the wind the gradient differs by exactly h^2 f per node.
  f.p.wind.on = false;
  VecX g0(f.z.size());
  Assembly out0{g0, hess};
  ASSERT_TRUE(assemble_terms(f.p, f.caches, f.z, out0));
  const double h2 = f.p.h * f.p.h;
  for (int i = 0; i < f.mesh.node_count(); ++i) {
    EXPECT_NEAR(g[2 * i] - g0[2 * i], -h2 * f.p.wind.force.x(), 1e-12);
    EXPECT_NEAR(g[2 * i + 1] - g0[2 * i + 1], -h2 * f.p.wind.force.y(), 1e-12);
  }
}

TEST(TermList, AnAppendedNodeTermPushesExplicitIntegration) {
  Fixture f;
  const VecX v = VecX::Zero(f.z.size());
  VecX with_wind, without;
  f.p.wind.on = true;
  explicit_gradient(f.p, f.caches, f.z, v, 0.0, with_wind);
  f.p.wind.on = false;
  explicit_gradient(f.p, f.caches, f.z, v, 0.0, without);
  for (int i = 0; i < f.mesh.node_count(); ++i) {
    EXPECT_NEAR(with_wind[2 * i] - without[2 * i], -f.p.wind.force.x(), 1e-9);
    EXPECT_NEAR(with_wind[2 * i + 1] - without[2 * i + 1], -f.p.wind.force.y(), 1e-9);
  }
}

TEST(TermList, AnAppendedNodeTermIsReportedUnderItsKind) {
  Fixture f;
  EnergyBins bins;
  energies_by_kind(f.p, f.caches, f.z, bins);
  EXPECT_NEAR(bins[EnergyKind::Load], wind_potential(f), 1e-12);
  EXPECT_GT(bins[EnergyKind::Elastic], 0.0);  // the list's own terms are still there
  EXPECT_NE(bins[EnergyKind::Gravity], 0.0);
}

}  // namespace
}  // namespace invfree
