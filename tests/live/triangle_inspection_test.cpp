// The live inspector's state without a window: a selected triangle's values are the
// core's analysis of the current state (updated as the body moves), an index off the mesh
// is not selected, and a mesh rebuild (another scene, n_seg) releases the selection while
// a reset keeps it.
#include "app/live/triangle_inspection.h"

#include <gtest/gtest.h>

#include "app/live/live_controller.h"
#include "scene_io/builtin_scenes.h"
#include "triangle_fields.h"

namespace invfree::live {
namespace {

LiveController compress_and_drop() {
  return LiveController({{"compress", *load_builtin_scene("compress").scene},
                         {"drop", *load_builtin_scene("drop").scene}},
                        0);
}

void expect_same_analysis(const StressAnalysis& a, const StressAnalysis& b) {
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.lame.mu, b.lame.mu);
  EXPECT_EQ(a.lame.lambda, b.lame.lambda);
  EXPECT_EQ(a.F, b.F);
  EXPECT_EQ(a.svd.U, b.svd.U);
  EXPECT_EQ(a.svd.sigma, b.svd.sigma);
  EXPECT_EQ(a.svd.V, b.svd.V);
  EXPECT_EQ(a.J, b.J);
  EXPECT_EQ(a.psi, b.psi);
  EXPECT_EQ(a.P, b.P);
  EXPECT_EQ(a.cauchy, b.cauchy);
  EXPECT_EQ(a.principal_stress, b.principal_stress);
  EXPECT_EQ(a.eigenvalues, b.eigenvalues);
  EXPECT_EQ(a.projected_eigenvalues, b.projected_eigenvalues);
  EXPECT_EQ(a.clamped, b.clamped);
}

TEST(TriangleInspection, FollowsTheStateAndMatchesTheCoresAnalysis) {
  LiveController lc = compress_and_drop();
  TriangleInspection in;
  EXPECT_EQ(in.inspected(), nullptr);
  const int t = lc.simulation().mesh.triangle_count() / 2;
  in.select(lc.simulation(), t, lc.mesh_generation());
  ASSERT_NE(in.inspected(), nullptr);
  EXPECT_EQ(in.inspected()->triangle, t);
  const Mat2 F0 = in.inspected()->analysis.F;
  for (int k = 0; k < 40; ++k) ASSERT_TRUE(lc.step_once());
  in.update(lc.simulation(), lc.mesh_generation());
  const Inspected& now = *in.inspected();
  EXPECT_EQ(now.step, 40);
  EXPECT_NE(now.analysis.F, F0);  // the body moved
  expect_same_analysis(now.analysis, analyze_triangle(lc.simulation(), t));
  const FiniteDifferenceErrors fd =
      finite_difference_errors(now.analysis.model, now.analysis.F, now.analysis.lame);
  EXPECT_EQ(now.fd.P, fd.P);
  EXPECT_EQ(now.fd.dPdF, fd.dPdF);
  EXPECT_LT(now.fd.P, 1e-5);
}

TEST(TriangleInspection, OffTheMeshIsNoSelection) {
  LiveController lc = compress_and_drop();
  TriangleInspection in;
  in.select(lc.simulation(), lc.simulation().mesh.triangle_count(), lc.mesh_generation());
  EXPECT_EQ(in.selected(), -1);
  in.select(lc.simulation(), -1, lc.mesh_generation());
  EXPECT_EQ(in.selected(), -1);
}

TEST(TriangleInspection, AMeshRebuildReleasesAResetKeeps) {
  LiveController lc = compress_and_drop();
  TriangleInspection in;
  in.select(lc.simulation(), 3, lc.mesh_generation());
  lc.step_once();
  lc.reset();
  in.update(lc.simulation(), lc.mesh_generation());
  EXPECT_EQ(in.selected(), 3);  // the same mesh: the same triangle
  SceneDef finer = lc.settings();
  finer.n_seg += 2;
  ASSERT_TRUE(lc.apply(finer));
  in.update(lc.simulation(), lc.mesh_generation());
  EXPECT_EQ(in.selected(), -1);
  in.select(lc.simulation(), 3, lc.mesh_generation());
  lc.select_scene(1);
  in.update(lc.simulation(), lc.mesh_generation());
  EXPECT_EQ(in.selected(), -1);
}

TEST(TriangleInspection, AMassSpringSceneHasNothingToShow) {
  LiveController lc({{"springs", *load_builtin_scene("course-1-mass-spring").scene}}, 0);
  ASSERT_FALSE(lc.settings().has_triangle_elasticity());
  if (lc.simulation().mesh.triangle_count() == 0) GTEST_SKIP() << "no triangles to select";
  TriangleInspection in;
  in.select(lc.simulation(), 0, lc.mesh_generation());
  ASSERT_NE(in.inspected(), nullptr);
  EXPECT_FALSE(in.inspected()->elastic);
}

}  // namespace
}  // namespace invfree::live
