// The linear modal analysis (core/modal/modal_analysis.h): linear.py's eigenvalues on its
// own cantilever (bilinear quads), the element matrices' invariants, linear triangles
// against Euler-Bernoulli's first bending frequency and against the quads on a fine mesh,
// a free body's three rigid modes, M-orthonormality and the eigen-equation's residual.
#include "modal/modal_analysis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "scene_io/scene_file.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

// tests/data/course/modes-cantilever.txt: linear.py's 8 eigenvalues (scripts/course_reference.py).
std::vector<double> reference_eigenvalues() {
  std::ifstream in(std::string(test::source_dir()) + "/tests/data/course/modes-cantilever.txt");
  std::vector<double> values;
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') values.push_back(std::stod(line));
  return values;
}

ModalModel cantilever(ModalElement element) {
  const SceneLoad load = load_scene("modes-cantilever");
  EXPECT_TRUE(load.scene) << load.error;
  std::string error;
  ModalModel model = scene_modal_model(*load.scene, element, &error);
  EXPECT_EQ(error, "");
  return model;
}

// linear.py's beam (width 1, length 15, clamped at y = 0, plane stress E 5e7, nu 0.3,
// rho 500) on an nx x ny grid, each cell split into two triangles.
ModalModel beam(int nx, int ny, ModalElement element) {
  const double mu = 5e7 / 2.6, lambda_star = 5e7 * 0.3 / 0.91;
  ModalModel m;
  m.element = element;
  m.density = 500.0;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.rest.emplace_back(1.0 * i / nx, 15.0 * j / ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int n0 = j * (nx + 1) + i, n1 = n0 + 1, n2 = n0 + nx + 1, n3 = n2 + 1;
      if (element == ModalElement::Quad) {
        m.quads.push_back({n0, n1, n3, n2});
        m.lame.push_back({mu, lambda_star});
      } else {
        m.triangles.push_back({n0, n1, n2});
        m.triangles.push_back({n1, n3, n2});
        m.lame.push_back({mu, lambda_star});
        m.lame.push_back({mu, lambda_star});
      }
    }
  for (int i = 0; i <= nx; ++i) m.fixed_dofs.insert(m.fixed_dofs.end(), {2 * i, 2 * i + 1});
  return m;
}

// Euler-Bernoulli's first bending frequency of the clamped-free beam (Hz):
// (1.8751^2 / 2 pi) sqrt(E I / (rho A L^4)), I = H^3 / 12, A = H (per unit thickness).
double euler_bernoulli_f1() {
  const double beta_l = 1.8751040687119611, E = 5e7, H = 1.0, L = 15.0, rho = 500.0;
  return beta_l * beta_l / (2 * std::numbers::pi) *
         std::sqrt(E * H * H / 12.0 / (rho * std::pow(L, 4)));
}

double f1(const ModalModel& model) {
  const ModalResult r = modal_analysis(model, 1);
  EXPECT_EQ(r.error, "");
  return r.error.empty() ? angular_frequency(r.eigenvalues[0]) / (2 * std::numbers::pi) : 0.0;
}

TEST(ModalAnalysis, QuadsReproduceLinearPyEigenvalues) {
  const std::vector<double> reference = reference_eigenvalues();
  ASSERT_EQ(reference.size(), 8u);
  const ModalModel model = cantilever(ModalElement::Quad);
  EXPECT_EQ(model.quads.size(), 150u);
  EXPECT_EQ(model.fixed_dofs.size(), 12u);  // the 6 nodes at y = 0
  const ModalResult r = modal_analysis(model, 8);
  ASSERT_EQ(r.error, "");
  double worst = 0.0;
  for (int k = 0; k < 8; ++k) {
    const double rel = std::abs(r.eigenvalues[k] - reference[k]) / reference[k];
    worst = std::max(worst, rel);
    EXPECT_LT(rel, 1e-8) << "mode " << k + 1 << ": " << r.eigenvalues[k] << " vs " << reference[k];
  }
  RecordProperty("max_relative_difference", std::to_string(worst));
  std::printf("linear.py's eigenvalues: max relative difference %.3g\n", worst);
}

TEST(ModalAnalysis, SceneBeamIsTheGridBeam) {
  // The scene (mesh file, mu and lambda* as 17 digits) and the grid built here agree.
  const ModalResult a = modal_analysis(cantilever(ModalElement::Triangle), 4);
  const ModalResult b = modal_analysis(beam(5, 30, ModalElement::Triangle), 4);
  ASSERT_EQ(a.error, "");
  ASSERT_EQ(b.error, "");
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(a.eigenvalues[k] / b.eigenvalues[k], 1.0, 1e-10);
}

TEST(ModalAnalysis, ElementMatricesHaveNoRigidEnergyAndTheirMass) {
  const Lame lame{3.0, 2.0};
  const std::array<Vec2, 3> t = {Vec2(0.1, 0.2), Vec2(1.3, 0.4), Vec2(0.5, 1.1)};
  const std::array<Vec2, 4> q = {Vec2(0, 0), Vec2(1.2, 0.1), Vec2(1.4, 0.9), Vec2(-0.1, 1.0)};
  const Mat6 kt = triangle_stiffness(t, lame), mt = triangle_mass(t, 7.0);
  const Mat8 kq = quad_stiffness(q, lame), mq = quad_mass(q, 7.0);
  const auto rigid = [](const auto& x, int which) {
    Eigen::VectorXd u(2 * x.size());
    for (size_t i = 0; i < x.size(); ++i)
      u.segment<2>(2 * i) = which == 0   ? Vec2(1, 0)
                            : which == 1 ? Vec2(0, 1)
                                         : Vec2(-x[i].y(), x[i].x());
    return u;
  };
  for (int w = 0; w < 3; ++w) {
    EXPECT_LT((kt * rigid(t, w)).norm(), 1e-12 * kt.norm());
    EXPECT_LT((kq * rigid(q, w)).norm(), 1e-12 * kq.norm());
  }
  const double area_t =
      0.5 * ((t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x());
  double area_q = 0.0;  // the shoelace formula
  for (int i = 0; i < 4; ++i)
    area_q += 0.5 * (q[i].x() * q[(i + 1) % 4].y() - q[(i + 1) % 4].x() * q[i].y());
  // u = (1, 0) everywhere: u^T M u is the element's mass.
  EXPECT_NEAR(rigid(t, 0).dot(mt * rigid(t, 0)), 7.0 * area_t, 1e-12);
  EXPECT_NEAR(rigid(q, 0).dot(mq * rigid(q, 0)), 7.0 * area_q, 1e-12);
  // Symmetric, and K positive on a stretch.
  EXPECT_LT((kt - kt.transpose()).norm(), 1e-12 * kt.norm());
  EXPECT_LT((kq - kq.transpose()).norm(), 1e-12 * kq.norm());
  Eigen::VectorXd stretch(6);
  stretch << t[0].x(), 0, t[1].x(), 0, t[2].x(), 0;  // u = (x, 0): eps_xx = 1
  EXPECT_NEAR(stretch.dot(kt * stretch), area_t * (lame.lambda + 2 * lame.mu), 1e-12);
}

TEST(ModalAnalysis, TrianglesConvergeToEulerBernoulli) {
  // Linear triangles are too stiff in bending (they lock): f1 comes out high and falls
  // toward the beam's value as the mesh is refined; linear.py's 5 x 30 is far off.
  const double eb = euler_bernoulli_f1();
  double last = 1e300;
  std::vector<double> errors;
  for (const int n : {1, 2, 4}) {
    const double f = f1(beam(5 * n, 30 * n, ModalElement::Triangle));
    errors.push_back(f / eb - 1);
    EXPECT_GT(f, eb);
    EXPECT_LT(f, last);
    last = f;
  }
  std::printf("triangles' f1 / Euler-Bernoulli - 1 at 5x30, 10x60, 20x120: %.4f %.4f %.4f\n",
              errors[0], errors[1], errors[2]);
  EXPECT_LT(errors.back(), 0.03);         // within a few percent at 20 x 120
  EXPECT_LT(errors[2], errors[1] / 2.5);  // second order in h: about 4x per halving
}

TEST(ModalAnalysis, TrianglesAndQuadsAgreeOnAFineMesh) {
  const ModalResult t = modal_analysis(beam(20, 120, ModalElement::Triangle), 4);
  const ModalResult q = modal_analysis(beam(20, 120, ModalElement::Quad), 4);
  ASSERT_EQ(t.error, "");
  ASSERT_EQ(q.error, "");
  for (int k = 0; k < 4; ++k) {
    std::printf("mode %d: triangles %.6g, quads %.6g Hz\n", k + 1,
                angular_frequency(t.eigenvalues[k]) / (2 * std::numbers::pi),
                angular_frequency(q.eigenvalues[k]) / (2 * std::numbers::pi));
    EXPECT_NEAR(t.eigenvalues[k] / q.eigenvalues[k], 1.0, 0.025) << "mode " << k + 1;
  }
}

TEST(ModalAnalysis, FreeBodyHasThreeRigidModes) {
  // compress's square has no [fixed] nodes: two translations and a rotation at 0.
  SceneLoad load = load_scene("compress");
  ASSERT_TRUE(load.scene) << load.error;
  for (const ModalElement element : {ModalElement::Triangle, ModalElement::Quad}) {
    std::string error;
    const ModalModel model = scene_modal_model(*load.scene, element, &error);
    ASSERT_EQ(error, "");
    EXPECT_TRUE(model.fixed_dofs.empty());
    const ModalResult r = modal_analysis(model, 5);
    ASSERT_EQ(r.error, "");
    EXPECT_LT(r.shift, 0.0);
    for (int k = 0; k < 3; ++k) EXPECT_LT(std::abs(r.eigenvalues[k]), 1e-8 * r.eigenvalues[3]);
    EXPECT_GT(r.eigenvalues[3], 0.0);
    // The three span the rigid motions: x and y translations and the rotation lie in them.
    const ModalMatrices mm = assemble_modal_matrices(model);
    const Eigen::MatrixXd rigid_modes = r.shapes.leftCols(3);
    for (int w = 0; w < 3; ++w) {
      VecX u(model.dof_count());
      for (size_t i = 0; i < model.rest.size(); ++i) {
        const Vec2& x = model.rest[i];
        u.segment<2>(2 * i) = w == 0 ? Vec2(1, 0) : w == 1 ? Vec2(0, 1) : Vec2(-x.y(), x.x());
      }
      // M-orthogonal projection onto the modes (they are M-orthonormal).
      const VecX projected = rigid_modes * (rigid_modes.transpose() * (mm.M * u));
      EXPECT_LT((u - projected).norm(), 1e-6 * u.norm()) << "rigid motion " << w;
    }
  }
}

TEST(ModalAnalysis, ModesAreMOrthonormalAndSolveTheEigenEquation) {
  for (const ModalElement element : {ModalElement::Triangle, ModalElement::Quad}) {
    const ModalModel model = cantilever(element);
    const ModalResult r = modal_analysis(model, 8);
    ASSERT_EQ(r.error, "");
    const ModalMatrices mm = assemble_modal_matrices(model);
    const Eigen::MatrixXd gram = r.shapes.transpose() * mm.M * r.shapes;
    EXPECT_LT((gram - Eigen::MatrixXd::Identity(8, 8)).cwiseAbs().maxCoeff(), 1e-9);
    for (int k = 0; k < 8; ++k) {
      VecX residual = mm.K * r.shapes.col(k) - r.eigenvalues[k] * (mm.M * r.shapes.col(k));
      for (int d : model.fixed_dofs) residual[d] = 0;  // the reactions
      EXPECT_LT(residual.norm(), 1e-8 * (mm.K * r.shapes.col(k)).norm()) << "mode " << k + 1;
      for (int d : model.fixed_dofs) EXPECT_EQ(r.shapes(d, k), 0.0);
      // Ascending; the largest entry positive.
      if (k > 0) {
        EXPECT_GE(r.eigenvalues[k], r.eigenvalues[k - 1]);
      }
      Eigen::Index at = 0;
      r.shapes.col(k).cwiseAbs().maxCoeff(&at);
      EXPECT_GT(r.shapes(at, k), 0.0);
    }
  }
}

TEST(ModalAnalysis, QuadPairingNeedsAGrid) {
  // The square's grid (alternating diagonals) pairs up; a CGAL-meshed disk does not.
  SceneLoad square = load_scene("compress");
  ASSERT_TRUE(square.scene);
  std::string error;
  const ModalModel q = scene_modal_model(*square.scene, ModalElement::Quad, &error);
  EXPECT_EQ(error, "");
  EXPECT_EQ(q.quads.size(), 16u);  // n_seg 4
  SceneDef disk = *square.scene;
  ASSERT_EQ(apply_override(disk, "mesh.shape=disk"), "");
  scene_modal_model(disk, ModalElement::Quad, &error);
  EXPECT_NE(error.find("has no partner"), std::string::npos) << error;
  scene_modal_model(disk, ModalElement::Triangle, &error);
  EXPECT_EQ(error, "");
  // Two triangles sharing a longest edge but forming a non-convex quad (a dart).
  const std::vector<Vec2> dart = {Vec2(0, 0), Vec2(2, 0), Vec2(1, 0.2), Vec2(1, 1)};
  const QuadPairing p = pair_triangles_into_quads(dart, {{0, 1, 3}, {1, 0, 2}});
  EXPECT_NE(p.error, "");
  EXPECT_TRUE(p.quads.empty());
}

TEST(ModalAnalysis, CountOutOfRangeAndMassSpringAreRefused) {
  const ModalModel model = beam(1, 1, ModalElement::Triangle);  // 4 nodes, 2 held: 4 free dofs
  EXPECT_EQ(model.free_dof_count(), 4);
  EXPECT_NE(modal_analysis(model, 4).error, "");
  EXPECT_NE(modal_analysis(model, 0).error, "");
  EXPECT_EQ(modal_analysis(model, 3).error, "");
  SceneLoad springs = load_scene("course-1-mass-spring");
  ASSERT_TRUE(springs.scene);
  std::string error;
  scene_modal_model(*springs.scene, ModalElement::Triangle, &error);
  EXPECT_NE(error.find("mass-spring"), std::string::npos) << error;
}

}  // namespace
}  // namespace invfree
