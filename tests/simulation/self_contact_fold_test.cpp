// Heavy (label `heavy`, release only): the default `compress` (self-contact on, as in every
// scene) at n_seg 64, 128 and 256 squashed to the ceiling's stop. Every accepted state is
// checked by the exact segment-segment test and det F > 0, and the run completes. With
// self-contact switched off the n_seg 64 run's bottom surface does pass through itself
// (what the term prevents).
#include <gtest/gtest.h>

#include "collision/intersection_check.h"
#include "potential/elasticity.h"
#include "scene/boundary.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"

namespace invfree {
namespace {

constexpr int kStepsToTheStop = 280;  // the ceiling reaches -0.7 at t = 2.6 s

// Steps until the stop; returns the first step whose state intersects (-1: none).
int first_intersecting_step(int n_seg, bool self_contact, int* max_newton) {
  SceneDef s = *load_builtin_scene("compress").scene;
  s.n_seg = n_seg;
  if (!self_contact) s.has_self_contact = false;  // on by default
  EXPECT_EQ(s.self_contact_on(), self_contact);
  Simulation sim = make_simulation(s);
  const Boundary boundary = find_boundary(sim.mesh);
  BroadPhaseGrid grid;
  std::vector<std::array<int, 2>> scratch;
  *max_newton = 0;
  for (int k = 1; k <= kStepsToTheStop; ++k) {
    const StepReport r = step(sim);
    EXPECT_EQ(r.status, StepStatus::Ok) << "n_seg " << n_seg << " step " << k << ": " << r.message;
    if (r.status != StepStatus::Ok) return -2;
    *max_newton = std::max(*max_newton, r.newton_iterations);
    for (int t = 0; t < sim.mesh.triangle_count(); ++t)
      EXPECT_GT(triangle_deformation_gradient(sim.mesh, sim.x.data(), t).determinant(), 0.0);
    if (find_self_intersection(boundary, sim.x, grid, scratch)) return k;
  }
  EXPECT_LE(sim.ceiling_nominal, s.ceiling_stop);
  return -1;
}

class FoldWithSelfContact : public ::testing::TestWithParam<int> {};

TEST_P(FoldWithSelfContact, NoAcceptedStateIntersects) {
  int max_newton = 0;
  EXPECT_EQ(first_intersecting_step(GetParam(), true, &max_newton), -1);
  EXPECT_LT(max_newton, 100);
  RecordProperty("max_newton_iterations", max_newton);
}

INSTANTIATE_TEST_SUITE_P(Compress, FoldWithSelfContact, ::testing::Values(64, 128, 256));

TEST(FoldWithoutSelfContact, PassesThroughItself) {
  int max_newton = 0;
  EXPECT_GT(first_intersecting_step(64, false, &max_newton), 0);
}

}  // namespace
}  // namespace invfree
