// Self-contact in whole steps (core/potential/self_contact.h): a body at rest or falling
// freely feels nothing (the run is bit-identical to one without the term), a folding
// compress keeps every boundary edge apart on every accepted state (exact test), and a
// contact that appears is kept outside the Hessian's pattern by PCG and grows the pattern of
// a direct solver.
#include <gtest/gtest.h>

#include "collision/intersection_check.h"
#include "potential/elasticity.h"
#include "scene/boundary.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"
#include "solver/step_workspace.h"

namespace invfree {
namespace {

SceneDef free_body(int n_seg, bool gravity) {
  SceneDef s = *load_builtin_scene("compress").scene;
  s.n_seg = n_seg;
  s.has_ground = s.has_ceiling = false;
  s.has_gravity = gravity;
  s.initial_velocity = Vec2(0.3, 0.2);
  return s;
}

void expect_same_run(SceneDef scene, int steps) {
  Simulation off = make_simulation(scene);
  scene.has_self_contact = true;
  scene.self_friction = 0.5;
  Simulation on = make_simulation(scene);
  for (int k = 0; k < steps; ++k) {
    ASSERT_EQ(step(off).status, StepStatus::Ok);
    ASSERT_EQ(step(on).status, StepStatus::Ok);
  }
  EXPECT_TRUE(on.x == off.x) << "self-contact changed the motion of a body that touches nothing";
  EXPECT_TRUE(on.v == off.v);
  EXPECT_EQ(on.workspace->newton.hessian.pattern_version, 0);
}

TEST(SelfContactStep, BodyMovingRigidlyFeelsNothing) {
  // dhat 5 cm on 3.1 cm edges: neighbours along the boundary are within the scene's dhat
  // (as at n_seg 256 with the default 1 cm), so only the per-pair dhat rule keeps them out.
  SceneDef s = free_body(32, false);
  s.dhat = 0.05;
  expect_same_run(s, 5);
}

TEST(SelfContactStep, BodyFallingFreelyFeelsNothing) {
  expect_same_run(free_body(64, true), 20);
}

TEST(SelfContactStep, FoldingCompressStaysIntersectionFree) {
  SceneDef s = *load_builtin_scene("compress").scene;
  s.n_seg = 40;  // the first size whose fold brings the boundary within dhat of itself
  s.has_self_contact = true;
  Simulation sim = make_simulation(s);
  const Boundary boundary = find_boundary(sim.mesh);
  BroadPhaseGrid grid;
  std::vector<std::array<int, 2>> scratch;
  double closest = INFINITY;
  for (int k = 0; k < 300; ++k) {
    const StepReport r = step(sim);
    ASSERT_EQ(r.status, StepStatus::Ok) << "step " << k << ": " << r.message;
    ASSERT_FALSE(find_self_intersection(boundary, sim.x, grid, scratch)) << "step " << k;
    for (int t = 0; t < sim.mesh.triangle_count(); ++t)
      ASSERT_GT(triangle_deformation_gradient(sim.mesh, sim.x.data(), t).determinant(), 0.0);
    closest = std::min(closest, min_self_gap(sim));
  }
  // The fold did bring the boundary within dhat of itself; its pairs outside the mesh's
  // pattern (point-point ones here, whose blocks there are zero; linear_solver_test's fold
  // at n_seg 64 has nonzero ones) stayed out of it with PCG: no rebuild, one analysis.
  EXPECT_LT(closest, s.dhat);
  EXPECT_GT(closest, 0.0);
  EXPECT_EQ(sim.workspace->newton.hessian.pattern_version, 0);
  EXPECT_EQ(sim.workspace->newton.analyses, 1);
}

// A direct solver's factor must hold every block: there the contacts grow the pattern and
// the solver analyses it again.
TEST(SelfContactStep, ADirectSolverGrowsThePattern) {
  SceneDef s = *load_builtin_scene("compress").scene;
  s.n_seg = 40;
  s.has_self_contact = true;
  s.linear_solver = LinearSolverKind::Ldlt;
  Simulation sim = make_simulation(s);
  for (int k = 0; k < 300; ++k) ASSERT_EQ(step(sim).status, StepStatus::Ok) << "step " << k;
  EXPECT_GT(sim.workspace->newton.hessian.pattern_version, 0);
  EXPECT_EQ(sim.workspace->newton.analyses, 1 + sim.workspace->newton.hessian.pattern_version);
  EXPECT_TRUE(sim.workspace->newton.hessian.couplings.empty());
}

}  // namespace
}  // namespace invfree
