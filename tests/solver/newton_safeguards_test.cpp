// Newton's safeguards (core/newton.h: step expansion, friction crossing stop) and the
// ceiling penalty's warm start (core/simulation.cpp) change the path to the minimum,
// never the stopping test: at every state a step returns, the direction of the
// unmodified projected Hessian, solved exactly by an independent factorisation, is below
// the tolerance. And they do what they are for: fewer Newton iterations where friction
// and buckling made Newton crawl, no re-doubling of the ceiling's penalty.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <algorithm>

#include "potential/incremental_potential.h"
#include "scene/scene.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"
#include "solver/step_workspace.h"

namespace invfree {
namespace {

SceneDef compress(int n_seg, bool safeguards, bool crossing_stop) {
  SceneDef s = *load_builtin_scene("compress").scene;
  s.n_seg = n_seg;
  s.step_expansion = safeguards;
  s.friction_crossing_stop = crossing_stop;
  return s;
}
SceneDef compress(int n_seg, bool safeguards) {
  return compress(n_seg, safeguards, safeguards);
}

// |p|_inf / h for p = -H^-1 g at the state the last step returned (its own problem:
// x_tilde, friction weights and ceiling state of that step).
double exact_residual(const Simulation& sim) {
  const StepProblem& p = sim.workspace->problem;
  SparseHessian hess = build_sparse_hessian(sim.mesh, p.ceiling.on);
  VecX g;
  ip_gradient_hessian(p, sim.workspace->caches, sim.workspace->z, g, hess);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(hess.matrix);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  const VecX dir = ldlt.solve(-g);
  return dir.lpNorm<Eigen::Infinity>() / p.h;
}

TEST(NewtonSafeguards, EveryReturnedStatePassesTheExactStoppingTest) {
  Simulation sim = make_simulation(compress(32, true));
  int stopped = 0, expanded = 0;
  for (int k = 0; k < 300; ++k) {
    const StepReport r = step(sim);
    ASSERT_EQ(r.status, StepStatus::Ok) << "step " << k;
    stopped += r.stopped_nodes;
    expanded += r.expanded_steps;
    ASSERT_LT(exact_residual(sim), sim.scene.tol) << "step " << k;
  }
  // The run exercised both safeguards (otherwise this test would prove nothing).
  EXPECT_GT(stopped, 0);
  EXPECT_GT(expanded, 0);
}

struct RunStats {
  int total = 0, worst = 0;
};
RunStats newton_iterations(const SceneDef& scene, int steps) {
  Simulation sim = make_simulation(scene);
  RunStats s;
  for (int k = 0; k < steps; ++k) {
    const StepReport r = step(sim);
    EXPECT_EQ(r.status, StepStatus::Ok) << "step " << k;
    s.total += r.newton_iterations;
    s.worst = std::max(s.worst, r.newton_iterations);
  }
  return s;
}

TEST(NewtonSafeguards, FewerIterationsWhereNewtonCrawled) {
  for (int n_seg : {16, 32}) {
    const RunStats with = newton_iterations(compress(n_seg, true), 300);
    const RunStats without = newton_iterations(compress(n_seg, false), 300);
    EXPECT_LT(with.total, without.total) << "n_seg " << n_seg;
    EXPECT_LT(with.worst, without.worst) << "n_seg " << n_seg;
  }
}

// The crossing stop on its own (step expansion on in both runs): the friction nodes'
// back-and-forth across zero slip was most of the iterations left.
TEST(NewtonSafeguards, CrossingStopEndsTheFrictionBackAndForth) {
  for (int n_seg : {16, 32}) {
    const RunStats with = newton_iterations(compress(n_seg, true, true), 300);
    const RunStats without = newton_iterations(compress(n_seg, true, false), 300);
    EXPECT_LT(with.total, without.total) << "n_seg " << n_seg;
    EXPECT_LT(with.worst, without.worst) << "n_seg " << n_seg;
  }
}

TEST(NewtonSafeguards, OffMeansTheLecturesPlainIteration) {
  Simulation sim = make_simulation(compress(16, false));
  for (int k = 0; k < 120; ++k) {
    const StepReport r = step(sim);
    ASSERT_EQ(r.status, StepStatus::Ok);
    EXPECT_EQ(r.stopped_nodes, 0);
    EXPECT_EQ(r.expanded_steps, 0);
  }
}

}  // namespace
}  // namespace invfree

namespace invfree {
namespace {

// The ceiling's penalty starts each step strong enough to hold the ceiling against the
// push the body gave it in the last step (core/simulation.cpp): once the ceiling
// presses on the body, Newton does not re-double k from a small start as the demo does.
int doublings_after_contact(SceneDef scene, int steps) {
  Simulation sim = make_simulation(scene);
  int after = 0;
  bool touched = false;
  for (int k = 0; k < steps; ++k) {
    const StepReport r = step(sim);
    EXPECT_EQ(r.status, StepStatus::Ok) << "step " << k;
    if (touched) after += r.penalty_doublings;
    double gap = 1e300;
    for (int i = 0; i < sim.mesh.node_count(); ++i)
      gap = std::min(gap, sim.ceiling_y - sim.x[2 * i + 1]);
    touched = touched || gap < scene.dhat;
  }
  return after;
}

TEST(CeilingPenalty, HoldsOnceTheCeilingPresses) {
  SceneDef stiff = compress(24, true);
  stiff.lame = lame_from_young_poisson(1e7, 0.4);
  // Without the warm start the stiff square needed 18 doublings after contact (and
  // `compress` at n_seg 256 reached Newton's cap of 100 iterations).
  EXPECT_LE(doublings_after_contact(compress(24, true), 300), 3);
  EXPECT_LE(doublings_after_contact(stiff, 300), 3);
}

}  // namespace
}  // namespace invfree
