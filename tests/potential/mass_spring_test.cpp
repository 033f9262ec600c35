// The mass-spring potential (core/potential/mass_spring.*): the spring set of the square
// mesh (edges and both diagonals of every cell, as the tutorial's square_mesh.generate
// makes it), each spring's gradient and Hessian against central finite differences over a
// sweep of lengths and directions, down to nearly zero length, and the closed-form PSD
// projection against the 4x4's eigen-decomposition clamped at zero.
#include "potential/mass_spring.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <set>
#include <utility>

#include "scene/mesh.h"

namespace invfree {
namespace {

using Mat4 = Eigen::Matrix4d;
using Vec4 = Eigen::Vector4d;

double energy4(const Spring& s, double k, const Vec4& q) {
  return spring_energy(s, k, q.head<2>(), q.tail<2>());
}

Vec4 gradient4(const Spring& s, double k, const Vec4& q) {
  const Vec2 gi = spring_gradient(s, k, q.head<2>(), q.tail<2>());
  return (Vec4() << gi, -gi).finished();
}

Mat4 hessian4(const Spring& s, double k, const Vec4& q, bool project) {
  const Mat2 a = spring_hessian_block(s, k, q.head<2>(), q.tail<2>(), project);
  Mat4 h;
  h << a, -a, -a, a;
  return h;
}

TEST(MassSpring, SpringsAreTheEdgesAndBothDiagonalsOfEveryCell) {
  for (int n_seg : {1, 2, 4, 7}) {
    const Mesh mesh = square_mesh(1.0, n_seg);
    const auto springs = mesh_springs(mesh);
    // n_seg (n_seg + 1) horizontal, as many vertical, 2 n_seg^2 diagonals.
    EXPECT_EQ(springs.size(), size_t(2 * n_seg * (n_seg + 1) + 2 * n_seg * n_seg)) << n_seg;
    std::set<std::pair<int, int>> seen;
    const int n = n_seg + 1;
    const double cell = 1.0 / n_seg;
    for (const Spring& s : springs) {
      EXPECT_LT(s.i, s.j);
      EXPECT_TRUE(seen.insert({s.i, s.j}).second) << "duplicate spring";
      const int di = std::abs(s.i / n - s.j / n), dj = std::abs(s.i % n - s.j % n);
      EXPECT_LE(di, 1);
      EXPECT_LE(dj, 1);
      EXPECT_NEAR(s.rest_length2, (di + dj) * cell * cell, 1e-15);
    }
    for (int i = 0; i < n_seg; ++i)  // both diagonals of cell (i, j)
      for (int j = 0; j < n_seg; ++j) {
        EXPECT_TRUE(seen.count({i * n + j, (i + 1) * n + j + 1}));
        EXPECT_TRUE(seen.count({i * n + j + 1, (i + 1) * n + j}));
      }
  }
}

TEST(MassSpring, EnergyIsTheTutorialsFormulaAndZeroAtRest) {
  const Spring s{0, 1, 0.04};
  const double k = 1e5;
  EXPECT_NEAR(energy4(s, k, Vec4(0.0, 0.0, 0.2, 0.0)), 0.0, 1e-20);
  // |d|^2 = 0.09: 1/2 k l^2 (0.09 / 0.04 - 1)^2
  EXPECT_NEAR(energy4(s, k, Vec4(0.1, 0.0, -0.2, 0.0)), 0.5 * k * 0.04 * 1.25 * 1.25, 1e-9);
}

TEST(MassSpring, DerivativesMatchFiniteDifferencesDownToNearlyZeroLength) {
  const double k = 2e4, l = 0.25;
  const Spring s{0, 1, l * l};
  for (double length : {1e-6, 1e-3, 0.05, 0.2, 0.25, 0.3, 0.6, 2.0})
    for (double angle : {0.0, 0.3, 1.2, 2.5, -2.0}) {
      const Vec2 xi(0.1, -0.4);
      const Vec2 xj = xi - length * Vec2(std::cos(angle), std::sin(angle));
      const Vec4 q = (Vec4() << xi, xj).finished();
      const Vec4 g = gradient4(s, k, q);
      const Mat4 h = hessian4(s, k, q, false);
      // The energy is a polynomial in x (quartic): central differences are exact up to
      // h^2 |f'''| / 6 and rounding, both far below the tolerance at this step, also across
      // d = 0 for the nearly degenerate springs.
      const double step = 1e-6;
      for (int a = 0; a < 4; ++a) {
        Vec4 qp = q, qm = q;
        qp[a] += step;
        qm[a] -= step;
        const double fd = (energy4(s, k, qp) - energy4(s, k, qm)) / (2 * step);
        const double scale = std::max({1.0, std::abs(g[a]), std::abs(fd)});
        EXPECT_NEAR(g[a], fd, 1e-6 * scale) << "gradient " << a << " length " << length;
        const Vec4 hfd = (gradient4(s, k, qp) - gradient4(s, k, qm)) / (2 * step);
        for (int b = 0; b < 4; ++b)
          EXPECT_NEAR(h(b, a), hfd[b], 1e-6 * std::max({1.0, h.cwiseAbs().maxCoeff()}))
              << "Hessian " << b << a << " length " << length << " angle " << angle;
      }
    }
}

TEST(MassSpring, ProjectionIsTheClampedEigenDecompositionOfTheFourByFour) {
  const double k = 1e3, l = 0.25;
  const Spring s{0, 1, l * l};
  for (double length : {0.0, 1e-8, 0.1, 0.2, 0.24, 0.25, 0.26, 1.0})
    for (double angle : {0.0, 0.7, 2.0}) {
      const Vec2 xi(0.0, 0.0);
      const Vec2 xj = xi + length * Vec2(std::cos(angle), std::sin(angle));
      const Vec4 q = (Vec4() << xi, xj).finished();
      Eigen::SelfAdjointEigenSolver<Mat4> eig(hessian4(s, k, q, false));
      const Mat4 expected = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() *
                            eig.eigenvectors().transpose();
      const Mat4 projected = hessian4(s, k, q, true);
      EXPECT_LT((projected - expected).cwiseAbs().maxCoeff(), 1e-9 * k / (l * l))
          << "length " << length << " angle " << angle;
      EXPECT_GE(Eigen::SelfAdjointEigenSolver<Mat4>(projected).eigenvalues().minCoeff(),
                -1e-9 * k / (l * l));
    }
}

TEST(MassSpring, SumOverTheMeshAssemblesEverySpring) {
  const Mesh mesh = square_mesh(1.0, 3);
  const auto springs = mesh_springs(mesh);
  const auto pairs = spring_node_pairs(springs);
  const SparseHessian hessian = build_sparse_hessian(mesh, false, pairs);
  const auto slots = spring_slots(springs, hessian);
  MassSpring m{true, 5e3, true, &springs, &slots};
  VecX x(2 * mesh.node_count());
  for (int i = 0; i < mesh.node_count(); ++i)
    x.segment<2>(2 * i) = Vec2(1.3 * mesh.rest[i].x() + 0.1 * std::sin(3.0 * i),
                               0.8 * mesh.rest[i].y() + 0.05 * std::cos(5.0 * i));
  VecX g = VecX::Zero(x.size());
  SparseHessian h = hessian;
  add_mass_spring_derivatives(m, x.data(), 1.0, g.data(), h.values());
  double e = 0.0;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(x.size(), x.size());
  for (const Spring& s : springs) {
    const Vec4 q = (Vec4() << x.segment<2>(2 * s.i), x.segment<2>(2 * s.j)).finished();
    e += energy4(s, m.stiffness, q);
    const Mat4 local = hessian4(s, m.stiffness, q, true);
    const int dof[4] = {2 * s.i, 2 * s.i + 1, 2 * s.j, 2 * s.j + 1};
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) dense(dof[r], dof[c]) += local(r, c);
  }
  EXPECT_NEAR(mass_spring_energy(m, x.data()), e, 1e-12 * e);
  EXPECT_LT((Eigen::MatrixXd(h.matrix) - dense).cwiseAbs().maxCoeff(), 1e-9);
  for (int a = 0; a < x.size(); ++a) {
    VecX xp = x, xm = x;
    xp[a] += 1e-7;
    xm[a] -= 1e-7;
    const double fd = (mass_spring_energy(m, xp.data()) - mass_spring_energy(m, xm.data())) / 2e-7;
    EXPECT_NEAR(g[a], fd, 1e-5 * std::max(1.0, std::abs(fd))) << a;
  }
}

}  // namespace
}  // namespace invfree

namespace invfree {
namespace {

// Hooke's law (the course's chapter 0, [mass_spring] law = "hooke"): E = 1/2 k (|d| - l)^2.
double hooke4(const Spring& s, double k, const Eigen::Vector4d& q) {
  return hooke_spring_energy(s, k, q.head<2>(), q.tail<2>());
}

Eigen::Vector4d hooke_gradient4(const Spring& s, double k, const Eigen::Vector4d& q) {
  const Vec2 gi = hooke_spring_gradient(s, k, q.head<2>(), q.tail<2>());
  return (Eigen::Vector4d() << gi, -gi).finished();
}

Eigen::Matrix4d hooke_hessian4(const Spring& s, double k, const Eigen::Vector4d& q, bool project) {
  const Mat2 a = hooke_spring_hessian_block(s, k, q.head<2>(), q.tail<2>(), project);
  Eigen::Matrix4d h;
  h << a, -a, -a, a;
  return h;
}

TEST(HookeSpring, EnergyIsHalfKTimesTheStretchSquared) {
  const Spring s{0, 1, 0.09};  // l = 0.3, simulator1.py's spring
  const double k = 1e5;
  EXPECT_NEAR(hooke4(s, k, Eigen::Vector4d(0.3, 0.0, 0.0, 0.0)), 0.0, 1e-20);
  EXPECT_NEAR(hooke4(s, k, Eigen::Vector4d(0.4, 0.0, 0.0, 0.0)), 0.5 * k * 0.01, 1e-9);
  EXPECT_NEAR(hooke4(s, k, Eigen::Vector4d(0.0, 0.1, 0.0, 0.0)), 0.5 * k * 0.04, 1e-9);
  // simulator1.py's force on the particle: -k (|x| - l) x / |x|.
  const Vec2 x(0.4, 0.0);
  const Vec2 force = -hooke_spring_gradient(s, k, x, Vec2::Zero());
  EXPECT_NEAR(force.x(), -k * 0.1, 1e-9);
  EXPECT_EQ(force.y(), 0.0);
}

TEST(HookeSpring, DerivativesMatchFiniteDifferences) {
  const double k = 2e4, l = 0.25;
  const Spring s{0, 1, l * l};
  for (double length : {1e-3, 0.05, 0.2, 0.25, 0.3, 0.6, 2.0})
    for (double angle : {0.0, 0.3, 1.2, 2.5, -2.0}) {
      const Vec2 xi(0.1, -0.4);
      const Vec2 xj = xi - length * Vec2(std::cos(angle), std::sin(angle));
      const Eigen::Vector4d q = (Eigen::Vector4d() << xi, xj).finished();
      const Eigen::Vector4d g = hooke_gradient4(s, k, q);
      const Eigen::Matrix4d h = hooke_hessian4(s, k, q, false);
      // |d| is smooth away from d = 0; the step is far below the shortest length tried.
      const double step = 1e-7;
      for (int a = 0; a < 4; ++a) {
        Eigen::Vector4d qp = q, qm = q;
        qp[a] += step;
        qm[a] -= step;
        const double fd = (hooke4(s, k, qp) - hooke4(s, k, qm)) / (2 * step);
        EXPECT_NEAR(g[a], fd, 1e-5 * std::max({1.0, std::abs(g[a]), std::abs(fd)}))
            << "gradient " << a << " length " << length;
        const Eigen::Vector4d hfd = (hooke_gradient4(s, k, qp) - hooke_gradient4(s, k, qm)) /
                                    (2 * step);
        for (int b = 0; b < 4; ++b)
          EXPECT_NEAR(h(b, a), hfd[b], 1e-5 * std::max(1.0, h.cwiseAbs().maxCoeff()))
              << "Hessian " << b << a << " length " << length << " angle " << angle;
      }
    }
}

TEST(HookeSpring, ProjectionIsTheClampedEigenDecompositionOfTheFourByFour) {
  const double k = 1e3, l = 0.25;
  const Spring s{0, 1, l * l};
  for (double length : {1e-8, 0.1, 0.2, 0.24, 0.25, 0.26, 1.0})
    for (double angle : {0.0, 0.7, 2.0}) {
      const Vec2 xi(0.0, 0.0);
      const Vec2 xj = xi + length * Vec2(std::cos(angle), std::sin(angle));
      const Eigen::Vector4d q = (Eigen::Vector4d() << xi, xj).finished();
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(hooke_hessian4(s, k, q, false));
      const Eigen::Matrix4d expected = eig.eigenvectors() *
                                       eig.eigenvalues().cwiseMax(0.0).asDiagonal() *
                                       eig.eigenvectors().transpose();
      const Eigen::Matrix4d projected = hooke_hessian4(s, k, q, true);
      // The across eigenvalue k (1 - l/|d|) reaches -1e10 at |d| = 1e-8: relative to it.
      const double scale = k * std::max(1.0, l / length);
      EXPECT_LT((projected - expected).cwiseAbs().maxCoeff(), 1e-9 * scale)
          << "length " << length << " angle " << angle;
      EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(projected).eigenvalues().minCoeff(),
                -1e-9 * k);
    }
  // Zero length: no direction; gradient and Hessian 0.
  const Eigen::Vector4d zero = Eigen::Vector4d::Zero();
  EXPECT_EQ(hooke_gradient4(s, k, zero), Eigen::Vector4d::Zero());
  EXPECT_EQ(hooke_hessian4(s, k, zero, true), Eigen::Matrix4d::Zero());
  EXPECT_EQ(hooke4(s, k, zero), 0.5 * k * l * l);
}

// The sums dispatch on the law: the term's energy and gradient are Hooke's per spring.
TEST(HookeSpring, TheTermSumsHookesSprings) {
  const Mesh mesh = square_mesh(1.0, 2);
  const auto springs = mesh_springs(mesh);
  const auto pairs = spring_node_pairs(springs);
  const SparseHessian hessian = build_sparse_hessian(mesh, false, pairs);
  const auto slots = spring_slots(springs, hessian);
  MassSpring m{true, 1e6, true, &springs, &slots, true};
  VecX x(2 * mesh.node_count());
  for (int i = 0; i < mesh.node_count(); ++i)
    x.segment<2>(2 * i) = Vec2(1.2 * mesh.rest[i].x() + 0.03 * std::sin(3.0 * i),
                               0.7 * mesh.rest[i].y() + 0.02 * std::cos(5.0 * i));
  double e = 0.0;
  VecX expected = VecX::Zero(x.size());
  for (const Spring& s : springs) {
    const Vec2 xi = x.segment<2>(2 * s.i), xj = x.segment<2>(2 * s.j);
    e += hooke_spring_energy(s, m.stiffness, xi, xj);
    expected.segment<2>(2 * s.i) += hooke_spring_gradient(s, m.stiffness, xi, xj);
    expected.segment<2>(2 * s.j) -= hooke_spring_gradient(s, m.stiffness, xi, xj);
  }
  EXPECT_NEAR(mass_spring_energy(m, x.data()), e, 1e-12 * e);
  VecX g = VecX::Zero(x.size());
  SparseHessian h = hessian;
  add_mass_spring_derivatives(m, x.data(), 1.0, g.data(), h.values());
  EXPECT_LT((g - expected).cwiseAbs().maxCoeff(), 1e-6);
  // Listed springs: rest lengths from the rest positions, in the given order.
  const auto listed = listed_springs(mesh, {{{4, 0}}, {{1, 2}}});
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_EQ(listed[0].i, 4);
  EXPECT_EQ(listed[0].j, 0);
  EXPECT_NEAR(listed[0].rest_length2, 0.5, 1e-15);
  const auto count = spring_counts(listed, mesh.node_count());
  EXPECT_EQ(count[0] + count[1] + count[2] + count[4], 4.0);
  EXPECT_EQ(count[3], 0.0);
}

}  // namespace
}  // namespace invfree
