// Reduced bases ([reduced], scene/reduced_basis.h; the course's chapter 9): the polynomial
// bases span exactly the polynomial displacements of their order; the modal basis is the
// rest Hessian's lowest eigenvectors (rigid modes first, orthonormal); a cut inside a
// degenerate group and the combinations a basis cannot run are refused; a reduced run never
// leaves x0 + span(B), and a basis that spans every unknown gives the full model's steps.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/initial_state.h"
#include "scene/reduced_basis.h"
#include "scene/scene_mesh.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"
#include "solver/step_workspace.h"

namespace invfree {
namespace {

SceneDef course9(const char* name) {
  SceneLoad load = load_builtin_scene(name);
  EXPECT_TRUE(load.scene) << load.error;
  return *load.scene;
}

// The distance of v from span(B), relative to |v|.
double off_span(const Eigen::MatrixXd& B, const VecX& v) {
  const VecX q = B.colPivHouseholderQr().solve(v);
  return (B * q - v).norm() / std::max(v.norm(), 1e-300);
}

VecX rest_positions(const Mesh& mesh) {
  VecX x(2 * mesh.node_count());
  for (int i = 0; i < mesh.node_count(); ++i) x.segment<2>(2 * i) = mesh.rest[i];
  return x;
}

TEST(ReducedBasis, PolynomialBasesSpanExactlyTheirDegree) {
  SceneDef s = course9("course-9-cubic");
  const Mesh mesh = scene_mesh(s);
  // u = (X^a Y^b, 0) and (0, X^a Y^b) for every degree a + b <= 3 lies in the cubic basis;
  // a quartic displacement does not, and a degree-2 one is outside the affine basis.
  auto field = [&](int a, int b, int d) {
    VecX u = VecX::Zero(2 * mesh.node_count());
    for (int i = 0; i < mesh.node_count(); ++i)
      u[2 * i + d] = std::pow(mesh.rest[i].x() + 0.3, a) * std::pow(mesh.rest[i].y() - 0.2, b);
    return u;
  };
  for (int order = 1; order <= 3; ++order) {
    s.reduced_order = order;
    const Eigen::MatrixXd B = build_reduced_basis(s, mesh).basis;
    ASSERT_EQ(B.cols(), polynomial_basis_size(order, 1));
    ASSERT_EQ(B.rows(), 2 * mesh.node_count());
    for (int a = 0; a <= order; ++a)
      for (int b = 0; a + b <= order; ++b)
        for (int d = 0; d < 2; ++d) EXPECT_LT(off_span(B, field(a, b, d)), 1e-12) << order;
    EXPECT_GT(off_span(B, field(order + 1, 0, 0)), 1e-3) << order;
    EXPECT_GT(off_span(B, field(0, order + 1, 1)), 1e-3) << order;
  }
}

TEST(ReducedBasis, ModalBasisIsTheRestHessiansLowestEigenvectors) {
  const SceneDef s = course9("course-9-modal");
  const Mesh mesh = scene_mesh(s);
  const ReducedBasisBuild build = build_reduced_basis(s, mesh);
  ASSERT_TRUE(build.error.empty()) << build.error;
  const Eigen::MatrixXd& B = build.basis;
  ASSERT_EQ(B.cols(), s.reduced_modes);
  EXPECT_LT((B.transpose() * B - Eigen::MatrixXd::Identity(B.cols(), B.cols())).norm(), 1e-10);
  const Eigen::SparseMatrix<double> H = rest_elastic_hessian(s, mesh);
  // Dense check of the whole spectrum at this size (242 unknowns).
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense{Eigen::MatrixXd(H)};
  const VecX& all = dense.eigenvalues();
  const double scale = all.cwiseAbs().maxCoeff();
  for (int k = 0; k < B.cols(); ++k) {
    EXPECT_NEAR(build.eigenvalues[k], all[k], 1e-9 * scale) << k;
    const VecX residual = H * B.col(k) - build.eigenvalues[k] * B.col(k);
    EXPECT_LT(residual.norm(), 1e-7 * scale) << k;
  }
  // Rigid modes first: translations and the infinitesimal rotation are in the span.
  for (int k = 0; k < 3; ++k) EXPECT_LT(std::abs(build.eigenvalues[k]), 1e-9 * scale) << k;
  VecX tx = VecX::Zero(B.rows()), rotation(B.rows());
  for (int i = 0; i < mesh.node_count(); ++i) {
    tx[2 * i] = 1.0;
    rotation.segment<2>(2 * i) = Vec2(-mesh.rest[i].y(), mesh.rest[i].x());
  }
  EXPECT_LT(off_span(B, tx), 1e-9);
  EXPECT_LT(off_span(B, rotation), 1e-9);
  // The span is the same whatever the solver's choice inside it: the projector onto the
  // dense solver's lowest 12 eigenvectors equals B B^T.
  const Eigen::MatrixXd V = dense.eigenvectors().leftCols(B.cols());
  EXPECT_LT((V * V.transpose() - B * B.transpose()).norm(), 1e-8);
}

std::string problem_of(const SceneDef& s) {
  const auto p = find_scene_problem(s);
  return p ? p->key + ": " + p->reason : "";
}

TEST(ReducedBasis, ACutInsideADegenerateGroupIsRefused) {
  SceneDef s = course9("course-9-modal");
  EXPECT_EQ(problem_of(s), "");
  // The square's spectrum: 3 rigid modes, then 893, 951.7 twice, ... (mode 5 and 6 equal).
  s.reduced_modes = 5;
  EXPECT_NE(problem_of(s).find("reduced.modes: 5 splits a degenerate group"), std::string::npos)
      << problem_of(s);
  s.reduced_modes = 2;  // inside the rigid modes
  EXPECT_NE(problem_of(s).find("degenerate"), std::string::npos) << problem_of(s);
  s.reduced_modes = 6;
  EXPECT_EQ(problem_of(s), "");
  s.reduced_modes = 241;  // the mesh has 242 unknowns
  EXPECT_NE(problem_of(s).find("reduced.modes: 241 modes of a mesh with 242 unknowns"),
            std::string::npos)
      << problem_of(s);
}

TEST(ReducedBasis, CombinationsABasisCannotRunAreRefused) {
  const SceneDef base = course9("course-9-affine");
  SceneDef s = base;
  s.has_ceiling = true;
  EXPECT_NE(problem_of(s).find("reduced.basis: a reduced basis has no ceiling"), std::string::npos);
  s = base;
  s.linear_solver = LinearSolverKind::Pcg;
  EXPECT_NE(problem_of(s).find("leave solver.linear_solver auto"), std::string::npos);
  s = base;
  s.integrator = Integrator::SymplecticEuler;
  EXPECT_NE(problem_of(s).find("no Newton step"), std::string::npos);
  s = base;
  s.reduced_basis = ReducedBasis::Modal;
  s.has_mass_spring = true;
  EXPECT_NE(problem_of(s).find("mass-spring"), std::string::npos);
}

TEST(ReducedRun, StaysInTheSubspaceAndTouchesTheGround) {
  for (const char* name : {"course-9-affine", "course-9-quadratic", "course-9-modal"}) {
    SceneDef s = course9(name);
    Simulation sim = make_simulation(s);
    const Eigen::MatrixXd B = build_reduced_basis(s, sim.mesh).basis;
    const VecX x0 = sim.x;
    double lowest = INFINITY;
    for (int k = 0; k < 60; ++k) {
      const StepReport r = step(sim);
      ASSERT_EQ(r.status, StepStatus::Ok) << name << " " << r.message;
      for (int i = 0; i < sim.mesh.node_count(); ++i) lowest = std::min(lowest, sim.x[2 * i + 1]);
    }
    EXPECT_LT(off_span(B, sim.x - x0), 1e-10) << name;
    EXPECT_LT(lowest, -0.98) << name;            // it fell to the ground (y = -1) ...
    EXPECT_GT(min_plane_gap(sim), 0.0) << name;  // ... and stays above it
  }
}

TEST(ReducedRun, AnAffineBodyStaysAffine) {
  SceneDef s = course9("course-9-affine");
  Simulation sim = make_simulation(s);
  for (int k = 0; k < 50; ++k) ASSERT_EQ(step(sim).status, StepStatus::Ok);
  // Every triangle has the same F, so det F has one value.
  const std::vector<double> det = triangle_det_f(sim);
  const auto [lo, hi] = std::minmax_element(det.begin(), det.end());
  EXPECT_LT(*hi - *lo, 1e-12);
  EXPECT_LT(*hi, 0.999);  // squashed by the impact, not rigid
  // The anchor triangle is carried by the same affine map: its corners' positions
  // reproduce the map at three nodes.
  const auto anchors = affine_anchor_triangle(sim.scene, sim.mesh, sim.x);
  ASSERT_TRUE(anchors.has_value());
  const auto rest_anchors = affine_anchor_triangle(sim.scene, sim.mesh, rest_positions(sim.mesh));
  ASSERT_TRUE(rest_anchors.has_value());
  // Map the rest anchors' frame to the current one and apply it to node 0.
  Mat2 rest_frame, frame;
  rest_frame << (*rest_anchors)[1] - (*rest_anchors)[0], (*rest_anchors)[2] - (*rest_anchors)[0];
  frame << (*anchors)[1] - (*anchors)[0], (*anchors)[2] - (*anchors)[0];
  const Mat2 F = frame * rest_frame.inverse();
  for (int i : {0, 37, 120}) {
    const Vec2 predicted = (*anchors)[0] + F * (sim.mesh.rest[i] - (*rest_anchors)[0]);
    EXPECT_LT((predicted - Vec2(sim.x.segment<2>(2 * i))).norm(), 1e-10) << i;
  }
  EXPECT_NEAR(F.determinant(), *lo, 1e-10);
  s.reduced_order = 2;
  EXPECT_FALSE(affine_anchor_triangle(s, sim.mesh, sim.x).has_value());
}

TEST(ReducedRun, TheIdentityBasisTakesTheFullModelsSteps) {
  // The reduced solve with B = I (dense LDL^T of the whole Hessian) against the sparse
  // solve: the same Newton iterations, and steps equal to within Newton's tolerance (the
  // two factorisations round differently, and contact amplifies it over the run).
  SceneDef s = course9("course-9-affine");
  s.reduced_basis = ReducedBasis::Full;
  s.n_seg = 4;
  s.tol = 1e-8;
  Simulation full = make_simulation(s), reduced = make_simulation(s);
  reduced.workspace->newton.reduced.basis =
      Eigen::MatrixXd::Identity(reduced.x.size(), reduced.x.size());
  for (int k = 0; k < 80; ++k) {
    const StepReport a = step(full), b = step(reduced);
    ASSERT_EQ(a.status, StepStatus::Ok);
    ASSERT_EQ(b.status, StepStatus::Ok);
    EXPECT_LE(std::abs(a.newton_iterations - b.newton_iterations), 1) << k;
    EXPECT_LT((full.x - reduced.x).lpNorm<Eigen::Infinity>(), 1e-9) << k;
  }
}

TEST(ReducedRun, ANewMaterialGetsItsOwnModes) {
  // The live sliders change mu and lambda without a new mesh (update_scene): the modal
  // basis, the rest Hessian's eigenvectors, must follow the material (its Poisson ratio
  // changes the modes' shapes), and the state must stay where it was.
  SceneDef s = course9("course-9-modal");
  Simulation sim = make_simulation(s);
  for (int k = 0; k < 5; ++k) ASSERT_EQ(step(sim).status, StepStatus::Ok);
  const VecX x = sim.x;
  SceneDef softer = s;
  softer.lame = lame_from_young_poisson(2e4, 0.2);
  update_scene(sim, softer);
  EXPECT_EQ(sim.x, x);
  const Eigen::MatrixXd& B = sim.workspace->newton.reduced.basis;
  const Eigen::MatrixXd fresh = build_reduced_basis(softer, sim.mesh).basis;
  ASSERT_EQ(B.cols(), fresh.cols());
  EXPECT_LT((B * B.transpose() - fresh * fresh.transpose()).norm(), 1e-8);
  const Eigen::MatrixXd old = build_reduced_basis(s, sim.mesh).basis;
  EXPECT_GT((B * B.transpose() - old * old.transpose()).norm(), 1e-3);
  for (int k = 0; k < 5; ++k) ASSERT_EQ(step(sim).status, StepStatus::Ok);
  EXPECT_LT(off_span(B, sim.x - make_simulation(softer).x), 1e-10);
}

TEST(ReducedBasis, MoreColumnsThanUnknownsIsRefused) {
  SceneDef s = course9("course-9-quadratic");
  s.n_seg = 1;  // 4 nodes, 8 unknowns; the quadratic basis has 12 columns
  EXPECT_NE(problem_of(s).find("reduced.order: the order-2 basis has 12 columns, more than the "
                               "mesh's 8 unknowns"),
            std::string::npos)
      << problem_of(s);
  s.n_seg = 2;  // 18 unknowns
  EXPECT_EQ(problem_of(s), "");
}

}  // namespace
}  // namespace invfree
