// The boundary loads (potential/boundary_load.h, scene/tractions.h): the follower pressure's
// energy is pressure times the loops' signed area, its gradient and Hessian match central
// differences, its projected Hessian is PSD and keeps the exact one's positive half; the
// dead load's nodal forces add up to the table's force and are spread by edge length.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "potential/term_sums.h"
#include "scene/scene_mesh.h"
#include "scene/tractions.h"
#include "tests/potential/problem_fixture.h"

namespace invfree {
namespace {

struct PressureFixture {
  Mesh mesh = square_mesh(1.0, 3);
  Boundary boundary = find_boundary(mesh);
  std::vector<PressureEdge> edges;
  VecX z;

  explicit PressureFixture(double p) {
    for (const auto& e : boundary.edges) edges.push_back({e[0], e[1], p});
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    z.resize(2 * mesh.node_count());
    for (int i = 0; i < mesh.node_count(); ++i)
      z.segment<2>(2 * i) = mesh.rest[i] + 0.05 * Vec2(u(rng), u(rng));
  }
  PressureLoad term(bool project) const {
    PressureLoad t;
    t.on = true;
    t.edges = &edges;
    t.factor = 0.7;
    t.project = project;
    return t;
  }
};

// The shoelace area of the deformed boundary loop (the square's outline, CCW).
double loop_area(const PressureFixture& f, const VecX& z) {
  double a = 0.0;
  for (const auto& e : f.boundary.edges)
    a += 0.5 * (z[2 * e[0]] * z[2 * e[1] + 1] - z[2 * e[1]] * z[2 * e[0] + 1]);
  return a;
}

TEST(PressureLoad, ItsEnergyIsPressureTimesTheEnclosedArea) {
  PressureFixture f(250.0);
  StepCaches caches;
  const TermPoint at{f.z, f.mesh, f.z, caches};
  const double area = loop_area(f, f.z);
  EXPECT_GT(area, 0.8);  // CCW: the body's area, not its negative
  EXPECT_NEAR(f.term(true).value(at, 2.0), 2.0 * 0.7 * 250.0 * area, 1e-12 * 350.0);
  // A rigid translation leaves it unchanged: the loop is closed.
  VecX moved = f.z;
  for (int i = 0; i < f.mesh.node_count(); ++i) moved.segment<2>(2 * i) += Vec2(3.0, -2.0);
  const TermPoint at2{moved, f.mesh, moved, caches};
  EXPECT_NEAR(f.term(true).value(at2, 1.0), f.term(true).value(at, 1.0), 1e-9);
}

// Central differences of the energy: the gradient to 1e-7 and, with projection off, the
// Hessian to 1e-6 (the energy is quadratic, so both are exact up to rounding of ~1e-10).
TEST(PressureLoad, GradientAndHessianMatchCentralDifferences) {
  for (double p : {250.0, -120.0}) {
    PressureFixture f(p);
    StepCaches caches;
    const int dofs = 2 * f.mesh.node_count();
    SparseHessian hessian = build_sparse_hessian(f.mesh, false);
    VecX g = VecX::Zero(dofs);
    hessian.set_zero();
    Assembly out(g, hessian);
    const PressureLoad term = f.term(false);
    term.add_derivatives({f.z, f.mesh, f.z, caches}, 1.0, out);
    const double eps = 1e-5;
    for (int k = 0; k < dofs; ++k) {
      VecX plus = f.z, minus = f.z;
      plus[k] += eps;
      minus[k] -= eps;
      const double fd = (term.value({plus, f.mesh, f.z, caches}, 1.0) -
                         term.value({minus, f.mesh, f.z, caches}, 1.0)) /
                        (2 * eps);
      EXPECT_NEAR(g[k], fd, 1e-7 * std::abs(p)) << "dof " << k;
      VecX gp = VecX::Zero(dofs), gm = VecX::Zero(dofs);
      term.add_gradient(plus, 1.0, gp);
      term.add_gradient(minus, 1.0, gm);
      const VecX column = (gp - gm) / (2 * eps);
      const Eigen::MatrixXd dense = Eigen::MatrixXd(hessian.matrix);
      for (int r = 0; r < dofs; ++r)
        EXPECT_NEAR(dense(r, k), column[r], 1e-6 * std::abs(p)) << r << "," << k;
    }
  }
}

// Projected, each edge keeps the PSD part of its block: the sum is PSD, and the exact
// Hessian minus the projected one is negative semidefinite (only the negative half went).
TEST(PressureLoad, TheProjectedHessianIsThePositiveHalf) {
  for (double p : {250.0, -120.0}) {
    PressureFixture f(p);
    StepCaches caches;
    const int dofs = 2 * f.mesh.node_count();
    auto assembled = [&](bool project) {
      SparseHessian h = build_sparse_hessian(f.mesh, false);
      VecX g = VecX::Zero(dofs);
      h.set_zero();
      Assembly out(g, h);
      f.term(project).add_derivatives({f.z, f.mesh, f.z, caches}, 1.0, out);
      return Eigen::MatrixXd(h.matrix);
    };
    const Eigen::MatrixXd projected = assembled(true), exact = assembled(false);
    const double scale = std::abs(p);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(projected).eigenvalues().minCoeff(),
              -1e-12 * scale);
    EXPECT_LT(
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(exact - projected).eigenvalues().maxCoeff(),
        1e-12 * scale);
    EXPECT_LT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(exact).eigenvalues().minCoeff(),
              -0.1 * scale);  // the exact one is indefinite: the projection did something
  }
}

SceneDef bar_with_traction(Vec2 force) {
  SceneDef s;
  s.shape.kind = ShapeKind::Rectangle;
  s.shape.width = 2.0;
  s.shape.height = 0.5;
  s.n_seg = 8;
  TractionDef t;
  t.box_min = Vec2(1.0, -0.25);
  t.box_max = Vec2(1.0, 0.25);
  t.force = force;
  s.tractions = {t};
  return s;
}

TEST(DeadLoad, TheNodalForcesAddUpToTheTableAndFollowEdgeLength) {
  const SceneDef s = bar_with_traction(Vec2(3.0, -4.0));
  const Mesh mesh = scene_mesh(s);
  const Boundary boundary = find_boundary(mesh);
  const std::vector<int> edges = traction_edges(s.tractions[0], mesh, boundary);
  ASSERT_GE(edges.size(), 2u);
  const VecX f = traction_node_forces(s, mesh, boundary);
  Vec2 total = Vec2::Zero();
  double loaded_length = 0.0;
  for (int i = 0; i < mesh.node_count(); ++i) {
    const Vec2 fi = f.segment<2>(2 * i);
    total += fi;
    if (fi != Vec2::Zero()) {
      EXPECT_NEAR(mesh.rest[i].x(), 1.0, 1e-12);  // only the loaded end's nodes
    }
  }
  for (int e : edges)
    loaded_length += (mesh.rest[boundary.edges[e][1]] - mesh.rest[boundary.edges[e][0]]).norm();
  EXPECT_NEAR(loaded_length, 0.5, 1e-12);
  EXPECT_NEAR(total.x(), 3.0, 1e-12);
  EXPECT_NEAR(total.y(), -4.0, 1e-12);
  // An end node carries half of its one edge's share: force * (length / 2) / 0.5.
  for (int e : edges)
    for (int end : boundary.edges[e]) {
      bool corner = std::abs(std::abs(mesh.rest[end].y()) - 0.25) < 1e-12;
      if (!corner) continue;
      const double share =
          (mesh.rest[boundary.edges[e][1]] - mesh.rest[boundary.edges[e][0]]).norm() / 0.5;
      EXPECT_NEAR(f[2 * end], 3.0 * share / 2, 1e-12);
    }
}

TEST(DeadLoad, ItsDerivativesAreMinusTheForce) {
  const double force[4] = {1.5, -2.0, 0.25, 4.0};
  const Vec2 rest[2] = {Vec2(0.0, 0.0), Vec2(0.1, -0.5)};
  DeadLoad load;
  load.on = true;
  load.force = force;
  load.origin = rest;
  load.factor = 0.5;
  NodeState s;
  s.index = 1;
  s.x = 0.3;
  s.y = -0.7;
  NodeDerivatives d;
  load.add_derivatives(s, 2.0, d);
  EXPECT_DOUBLE_EQ(d.gx, -2.0 * 0.5 * 0.25);
  EXPECT_DOUBLE_EQ(d.gy, -2.0 * 0.5 * 4.0);
  EXPECT_EQ(d.hxx, 0.0);
  // The work from the rest position: -f.(x - X).
  EXPECT_DOUBLE_EQ(load.value(s), -0.5 * (0.25 * (0.3 - 0.1) + 4.0 * (-0.7 + 0.5)));
}

}  // namespace
}  // namespace invfree
