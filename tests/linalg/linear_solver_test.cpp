// The Newton linear solve: every backend solves the system; PCG's inexact direction
// never makes Newton stop where the exact direction would not (pcg.h's error
// bound), is always a descent direction, and reuses its factorisation; a run with each
// solver keeps every invariant.
#include "linalg/linear_solver.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include "potential/incremental_potential.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"
#include "solver/step_workspace.h"

namespace invfree {
namespace {

// The Newton system of a compressed `compress` state (ground and ceiling contacts, friction).
struct System {
  Simulation sim;
  Eigen::SparseMatrix<double> H;
  VecX g, b;
  double lambda_min = 0.0;
  explicit System(int n_seg, int steps = 150, double perturb = 0.0) {
    SceneDef s = *load_builtin_scene("compress").scene;
    s.n_seg = n_seg;
    s.linear_solver = LinearSolverKind::Ldlt;
    sim = make_simulation(s);
    for (int k = 0; k < steps; ++k) EXPECT_EQ(step(sim).status, StepStatus::Ok);
    VecX z(sim.workspace->problem.dof_count());
    z.head(sim.x.size()) = sim.x + perturb * s.h * sim.v;  // part of a step ahead: not the minimum
    z[sim.x.size()] = sim.ceiling_y;
    ip_gradient_hessian(sim.workspace->problem, sim.workspace->caches, z, g, sim.workspace->newton.hessian);
    H = sim.workspace->newton.hessian.matrix;
    b = -g;
    lambda_min =
        hessian_lower_bound(sim.workspace->problem, sim.workspace->newton.min_node_mass);
  }
};

// Reference solution by Eigen's own sparse LDL^T (independent of the backends in core/linalg).
VecX dense_solve(const Eigen::SparseMatrix<double>& H, const VecX& b) {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(H);
  return ldlt.solve(b);
}

TEST(LinearSolver, EveryBackendSolvesTheNewtonSystem) {
  const System sys(12);
  const VecX exact = dense_solve(sys.H, sys.b);
  for (LinearSolverKind kind : {LinearSolverKind::Ldlt, LinearSolverKind::Cholmod,
                                LinearSolverKind::Pcg, LinearSolverKind::Auto}) {
    LinearSolver solver;
    solver.setup(sys.H, kind, true);
    LinearSolveStats stats;
    SolveRequest request;
    request.forcing = 1e-13;  // no stopping threshold: as exact as a direct solve
    VecX x;
    ASSERT_TRUE(solver.solve(sys.H, sys.b, x, request, stats)) << linear_solver_name(kind);
    EXPECT_LT((x - exact).norm(), 1e-9 * exact.norm()) << solver.backend_name();
    EXPECT_GE(stats.factorizations, 1);
  }
}

TEST(LinearSolver, BackendNamesFollowTheRequestAndTheProjection) {
  const System sys(6, 1);
  LinearSolver s;
  s.setup(sys.H, LinearSolverKind::Auto, true);
  EXPECT_STREQ(s.backend_name(), "pcg+ldlt");
  s.setup(sys.H, LinearSolverKind::Auto, false);  // exact Hessian, maybe indefinite: direct LDL^T
  EXPECT_STREQ(s.backend_name(), "ldlt");
  s.setup(sys.H, LinearSolverKind::Cholmod, true);
  EXPECT_STREQ(s.backend_name(), "cholmod");
  s.setup(sys.H, LinearSolverKind::Ldlt, true);
  EXPECT_STREQ(s.backend_name(), "ldlt");
  for (bool positive_definite : {true, false}) {  // PCG's factor is always the LDL^T
    s.setup(sys.H, LinearSolverKind::Pcg, positive_definite);
    EXPECT_STREQ(s.backend_name(), "pcg+ldlt");
  }
}

// Newton stops when |p|_inf < threshold. With a reused (stale) factorisation PCG is
// inexact, yet its stop decision must be the exact solution's whenever it says "stop".
TEST(Pcg, NeverStopsNewtonWhereTheExactDirectionWouldNot) {
  const System old_sys(32, 128), sys(32, 130, 0.5);
  const VecX exact = dense_solve(sys.H, sys.b);
  const double p_inf = exact.lpNorm<Eigen::Infinity>();
  int stops = 0, goes = 0;
  for (double ratio : {0.5, 0.9, 0.99, 0.999, 1.001, 1.01, 1.1, 2.0, 10.0}) {
    LinearSolver solver;
    solver.setup(old_sys.H, LinearSolverKind::Pcg, true);
    LinearSolveStats stats;
    SolveRequest warm;
    VecX x;
    ASSERT_TRUE(solver.solve(old_sys.H, old_sys.b, x, warm, stats));  // factorises the old matrix
    SolveRequest request;
    request.threshold = ratio * p_inf;
    request.lambda_min = sys.lambda_min;
    request.forcing = 0.3;  // a loose direction whenever Newton goes on
    ASSERT_TRUE(solver.solve(sys.H, sys.b, x, request, stats));
    EXPECT_EQ(stats.factorizations, 1) << "the stale factor should have been reused";
    const bool pcg_stops = x.lpNorm<Eigen::Infinity>() < request.threshold;
    if (pcg_stops) {
      ++stops;
      EXPECT_LT(p_inf, request.threshold)
          << "ratio " << ratio << ": PCG stopped Newton, the exact p would not";
    } else {
      ++goes;
    }
    // Every direction descends: g.p = -b.p < 0.
    EXPECT_GT(sys.b.dot(x), 0.0) << "ratio " << ratio;
  }
  EXPECT_GT(stops, 0);
  EXPECT_GT(goes, 0);
}

TEST(Pcg, ReusesOneFactorisationAcrossNearbySystems) {
  // The Newton systems at the states of consecutive steps of one run (compression phase).
  System sys(32, 100);
  LinearSolver solver;
  solver.setup(sys.H, LinearSolverKind::Pcg, true);
  LinearSolveStats stats;
  const int solves = 10;
  for (int k = 0; k < solves; ++k) {
    ASSERT_EQ(step(sys.sim).status, StepStatus::Ok);
    VecX z(sys.sim.workspace->problem.dof_count()), g;
    z.head(sys.sim.x.size()) = sys.sim.x;
    z[sys.sim.x.size()] = sys.sim.ceiling_y;
    ip_gradient_hessian(sys.sim.workspace->problem, sys.sim.workspace->caches, z, g, sys.sim.workspace->newton.hessian);
    const Eigen::SparseMatrix<double>& H = sys.sim.workspace->newton.hessian.matrix;
    const VecX b = -g;
    SolveRequest request;
    request.forcing = 1e-2;  // Newton's forcing term (relative model decrease of a CG step)
    VecX x;
    ASSERT_TRUE(solver.solve(H, b, x, request, stats));
    // An inexact Newton direction: close to the exact one in H's energy norm.
    const VecX exact = dense_solve(H, b);
    const VecX e = x - exact;
    EXPECT_LE(std::sqrt(e.dot(H * e)), 0.2 * std::sqrt(exact.dot(H * exact))) << "step " << k;
    EXPECT_GT(b.dot(x), 0.0) << "step " << k;
  }
  EXPECT_LE(stats.factorizations, 3) << "the factorisation should be reused across steps";
  EXPECT_GT(stats.pcg_iterations, solves);
}

// A folded `compress` (n_seg 64, self-contact) 30 steps after its contact blocks first lay
// outside the mesh's pattern (Newton keeps them as couplings, SparseHessian::couplings):
// the fold pressed together (n_seg 40 and 48 fold too, but their pairs outside the pattern
// are point-point ones whose blocks there are zero).
struct FoldSystem {
  Simulation sim;
  VecX z;
  explicit FoldSystem() {
    SceneDef s = *load_builtin_scene("compress").scene;
    s.n_seg = 64;
    s.has_self_contact = true;
    sim = make_simulation(s);
    for (int k = 0; k < 300 && sim.workspace->newton.hessian.couplings.empty(); ++k)
      EXPECT_EQ(step(sim).status, StepStatus::Ok);
    for (int k = 0; k < 30; ++k) EXPECT_EQ(step(sim).status, StepStatus::Ok);
    z.resize(sim.workspace->problem.dof_count());
    z.head(sim.x.size()) = sim.x + 0.5 * s.h * sim.v;  // part of a step ahead
    z[sim.x.size()] = sim.ceiling_y;
    begin_terms(sim.workspace->problem, sim.workspace->caches, z);  // the candidates there
  }
};

// The pattern plus the couplings is the matrix the pattern would be rebuilt into, entry
// for entry; PCG on it (its factor never holding the couplings) solves as a direct solve
// of that rebuilt matrix does; the direct backends refuse couplings.
TEST(Pcg, SolvesWithContactCouplingsOutsideThePattern) {
  FoldSystem fold;
  StepWorkspace& ws = *fold.sim.workspace;
  ASSERT_FALSE(ws.newton.hessian.couplings.empty()) << "the fold brought no contact";
  EXPECT_EQ(ws.newton.hessian.pattern_version, 0) << "PCG's Hessian should not have grown";
  SparseHessian kept = ws.newton.hessian;
  kept.keep_couplings = true;
  VecX g_kept, g_rebuilt;
  ip_gradient_hessian(ws.problem, ws.caches, fold.z, g_kept, kept);
  ASSERT_FALSE(kept.couplings.empty());
  EXPECT_EQ(kept.pattern_version, 0);
  SparseHessian rebuilt = ws.newton.hessian;
  rebuilt.keep_couplings = false;
  ip_gradient_hessian(ws.problem, ws.caches, fold.z, g_rebuilt, rebuilt);
  EXPECT_EQ(rebuilt.pattern_version, 1);
  EXPECT_TRUE(rebuilt.couplings.empty());
  EXPECT_TRUE(g_kept == g_rebuilt);
  Eigen::SparseMatrix<double> merged = kept.matrix;
  for (const NodeCoupling& c : kept.couplings)
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        merged.coeffRef(2 * c.row_node + a, 2 * c.col_node + b) += c.block(a, b);
  const Eigen::SparseMatrix<double> difference = merged - rebuilt.matrix;
  EXPECT_EQ(difference.coeffs().cwiseAbs().maxCoeff(), 0.0);
  VecX y;
  const VecX v = VecX::Random(kept.matrix.rows());
  multiply_hessian(kept, v, y);
  EXPECT_LT((y - rebuilt.matrix * v).norm(), 1e-12 * y.norm());

  const VecX b = -g_kept;
  const VecX exact = dense_solve(rebuilt.matrix, b);
  LinearSolver pcg;
  pcg.setup(kept.matrix, LinearSolverKind::Auto, true);
  ASSERT_STREQ(pcg.backend_name(), "pcg+ldlt");
  LinearSolveStats stats;
  SolveRequest request;
  request.forcing = 1e-13;  // as exact as a direct solve
  request.couplings = kept.couplings;
  VecX x;
  ASSERT_TRUE(pcg.solve(kept.matrix, b, x, request, stats));
  EXPECT_LT((x - exact).norm(), 1e-9 * exact.norm());
  // Without the couplings PCG solves another system (the test can tell).
  SolveRequest without = request;
  without.couplings = {};
  VecX x_without;
  ASSERT_TRUE(pcg.solve(kept.matrix, b, x_without, without, stats));
  EXPECT_GT((x_without - exact).norm(), 1e-6 * exact.norm());
  for (LinearSolverKind kind : {LinearSolverKind::Ldlt, LinearSolverKind::Cholmod}) {
    LinearSolver direct;
    direct.setup(kept.matrix, kind, true);
    EXPECT_FALSE(direct.solve(kept.matrix, b, x, request, stats)) << linear_solver_name(kind);
  }
}

double max_speed(const Simulation& sim) {
  double v = 0;
  for (int i = 0; i < sim.mesh.node_count(); ++i) v = std::max(v, sim.v.segment<2>(2 * i).norm());
  return v;
}

TEST(Simulation, EveryLinearSolverKeepsTheInvariantsAndComesToRest) {
  for (LinearSolverKind kind : {LinearSolverKind::Auto, LinearSolverKind::Ldlt,
                                LinearSolverKind::Cholmod, LinearSolverKind::Pcg}) {
    SceneDef s = *load_builtin_scene("compress").scene;
    s.n_seg = 10;
    s.linear_solver = kind;
    Simulation sim = make_simulation(s);
    for (int k = 0; k < 600; ++k) {
      const StepReport r = step(sim);
      ASSERT_EQ(r.status, StepStatus::Ok)
          << linear_solver_name(kind) << " step " << k << ": " << r.message;
      ASSERT_LT(r.residual, s.tol);
      for (const auto& t : sim.mesh.triangles) {
        const Vec2 a = sim.x.segment<2>(2 * t[1]) - sim.x.segment<2>(2 * t[0]);
        const Vec2 c = sim.x.segment<2>(2 * t[2]) - sim.x.segment<2>(2 * t[0]);
        ASSERT_GT(a.x() * c.y() - a.y() * c.x(), 0.0) << linear_solver_name(kind) << " step " << k;
      }
      for (int i = 0; i < sim.mesh.node_count(); ++i) {
        ASSERT_GT(sim.x[2 * i + 1], s.ground_y);
        ASSERT_LT(sim.x[2 * i + 1], sim.ceiling_y);
      }
    }
    EXPECT_LT(max_speed(sim), 1e-2) << linear_solver_name(kind);
    EXPECT_NEAR(sim.ceiling_y, s.ceiling_stop, 0.01) << linear_solver_name(kind);
  }
}

TEST(Simulation, ExactHessianRunsWithEverySolverThatAcceptsIt) {
  // Projection "none" may give an indefinite Hessian: auto uses LDL^T; a forced PCG falls
  // back to its factorisation when CG meets negative curvature.
  for (LinearSolverKind kind : {LinearSolverKind::Auto, LinearSolverKind::Pcg}) {
    SceneDef s = *load_builtin_scene("drop").scene;
    s.projection = HessianProjection::None;
    s.n_seg = 6;
    s.linear_solver = kind;
    Simulation sim = make_simulation(s);
    for (int k = 0; k < 150; ++k) {
      const StepReport r = step(sim);
      ASSERT_EQ(r.status, StepStatus::Ok)
          << linear_solver_name(kind) << " step " << k << ": " << r.message;
    }
  }
}

}  // namespace
}  // namespace invfree
