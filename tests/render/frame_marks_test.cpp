// What a frame marks besides the colours, without GL (issue 32): the method that stepped it
// on the panel, each body's own material, a failed run's last frame, inverted triangles
// that leave the body visible, and the bodies' paths that show what friction between them
// did (stack against stack-friction).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/render/camera.h"
#include "app/render/frame_text.h"
#include "app/render/frame_vertices.h"
#include "app/render/renderer.h"
#include "app/render/text_atlas.h"
#include "app/render/view_choices.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "simulation.h"
#include "triangle_fields.h"

namespace invfree::render {
namespace {

FrameVertices build(const FrameState& state, const DrawOptions& options = {}) {
  static TextAtlas atlas;
  FrameVertices v;
  v.font_sizes = {31, 21, 18};
  if (atlas.width() == 0) atlas.build(v.font_sizes);
  v.atlas = &atlas;
  const FrameLayout L = frame_layout(1280, 720);
  build_frame_vertices(v, state, L, scene_camera(state.scene, L), options);
  return v;
}

bool has(const std::vector<std::string>& words, const std::string& w) {
  return std::find(words.begin(), words.end(), w) != words.end();
}
bool has_prefix(const std::vector<std::string>& words, const std::string& prefix) {
  return std::any_of(words.begin(), words.end(),
                     [&](const std::string& w) { return w.rfind(prefix, 0) == 0; });
}

SceneDef builtin(const char* name) {
  const SceneLoad load = load_builtin_scene(name);
  EXPECT_TRUE(load.scene) << load.error;
  return *load.scene;
}

FrameState state_of(const SceneDef& scene) {
  Simulation sim = make_simulation(scene);
  return capture_frame_state(sim);
}

TEST(FrameMarks, PanelNamesTheIntegratorProjectionAndFilter) {
  SceneDef s = builtin("compress");
  auto words = build(state_of(s)).words;
  EXPECT_TRUE(has(words, "implicit Euler"));
  EXPECT_TRUE(has(words, "diagonal projection, filter on"));
  s.projection = HessianProjection::None;
  s.inversion_filter = false;
  words = build(state_of(s)).words;
  EXPECT_TRUE(has(words, "no projection, filter off"));
  s.integrator = Integrator::SymplecticEuler;
  words = build(state_of(s)).words;
  EXPECT_TRUE(has(words, "symplectic Euler"));
  EXPECT_FALSE(has(words, "implicit Euler"));
}

TEST(FrameMarks, PerBodyMaterialsAreLabelledInPlaceOfTheScenes) {
  SceneDef s = builtin("stack");
  ASSERT_EQ(s.bodies.size(), 2u);
  s.bodies[0].lame = Lame{1000.0, 4000.0};
  s.bodies[1].lame = Lame{50000.0, 200000.0};
  const auto words = build(state_of(s)).words;
  EXPECT_TRUE(has(words, "body 1: μ 1.00 kPa, λ 4.00 kPa"));
  EXPECT_TRUE(has(words, "body 2: μ 50.0 kPa, λ 200 kPa"));
  EXPECT_FALSE(has_prefix(words, "μ = "));  // the scene's, which no body uses
  // Without their own materials: the scene's.
  EXPECT_TRUE(has_prefix(build(state_of(builtin("stack"))).words, "μ = "));
}

TEST(FrameMarks, FrictionBetweenBodiesIsNamed) {
  EXPECT_TRUE(
      has(build(state_of(builtin("stack-friction"))).words, "between bodies: friction μ = 0.4"));
  EXPECT_TRUE(has(build(state_of(builtin("stack"))).words, "between bodies: no friction"));
}

// Vertices of exactly this colour.
size_t count_color(const FrameVertices& v, Rgba c) {
  return std::count_if(v.shapes.begin(), v.shapes.end(), [&](const ShapeVertex& p) {
    return p.c.r == c.r && p.c.g == c.g && p.c.b == c.b && p.c.a == c.a;
  });
}

TEST(FrameMarks, AFailedStateIsMarkedInThePicture) {
  FrameState state = state_of(builtin("compress"));
  const FrameVertices normal = build(state);
  state.failure = "step 33 failed: penetrated: node 3 below the ground";
  const FrameVertices failed = build(state);
  EXPECT_TRUE(has(failed.words, "RUN FAILED: step 33 failed: penetrated: node 3 below the ground"));
  EXPECT_FALSE(has_prefix(normal.words, "RUN FAILED"));
  const Rgba red{0.80f, 0.04f, 0.06f, 1.0f};
  EXPECT_EQ(count_color(normal, red), 0u);
  EXPECT_GE(count_color(failed, red), 5u * 6u);  // the border's four sides and the banner
  // A long reason is cut to the picture's width, not left to run under the panel.
  state.failure = std::string(400, 'x');
  const FrameVertices long_one = build(state);
  ASSERT_TRUE(has_prefix(long_one.words, "RUN FAILED: xxx"));
  for (const auto& w : long_one.words) {
    if (w.rfind("RUN FAILED", 0) == 0) {
      EXPECT_LT(w.size(), 200u);
    }
  }
}

TEST(FrameMarks, ATitledViewHasItsHeadingAboveAFailureBanner) {
  // render --compare's views: the method and what it is over the world's top, and a failed
  // side's banner below them (not over them).
  FrameState state = state_of(builtin("compress"));
  DrawOptions titled;
  titled.title = {"no-projection", "no projection (plain Newton) + inversion filter"};
  EXPECT_FALSE(has(build(state).words, "no-projection"));
  const FrameVertices plain = build(state, titled);
  EXPECT_TRUE(has(plain.words, "no-projection"));
  EXPECT_TRUE(has(plain.words, "no projection (plain Newton) + inversion filter"));
  state.failure = "step 22 failed: newton-failed: no descent";
  const FrameVertices failed = build(state, titled);
  EXPECT_TRUE(has(failed.words, "no-projection"));
  EXPECT_TRUE(has(failed.words, "RUN FAILED: step 22 failed: newton-failed: no descent"));
  const FrameLayout L = frame_layout(1280, 720);
  const double band = title_band_height(L);
  const float border = float(std::max(3.0, std::round(6.0 * L.scale)));
  bool banner_at_band = false;
  for (const ShapeVertex& p : failed.shapes) {
    if (!(p.c.r == 0.80f && p.c.g == 0.04f && p.c.b == 0.06f)) continue;
    banner_at_band = banner_at_band || p.y == float(band);
    EXPECT_FALSE(p.y > border && p.y < float(band)) << "red inside the heading at y " << p.y;
  }
  EXPECT_TRUE(banner_at_band);
}

TEST(FrameMarks, ManyLargeInvertedTrianglesAreOutlinedNotRinged) {
  // Every triangle of a coarse square inverted (mirrored): each is large on screen, so its
  // green fill shows it; rings around all of them hid the body.
  FrameState state = state_of(builtin("compress"));
  for (double& d : state.det_f) d = -0.5;
  const FrameVertices v = build(state);
  const Rgba green = rgba(kInvertedColor);
  const size_t legend = count_color(build(state_of(builtin("compress"))), green);  // the swatch
  // Only the fills are green (3 vertices each): no ring strokes.
  EXPECT_EQ(count_color(v, green), legend + 3 * state.triangles.size());
  // One inverted sliver: ringed, so that it is found at a glance.
  FrameState sliver = state_of(builtin("compress"));
  const auto tri = sliver.triangles[0];
  sliver.x[2 * tri[2]] = sliver.x[2 * tri[0]] + 1e-4;
  sliver.x[2 * tri[2] + 1] = sliver.x[2 * tri[0] + 1] + 1e-4;
  sliver.det_f[0] = -1e-3;
  EXPECT_GT(count_color(build(sliver), green), legend + 3u);
}

TEST(BodyPathsTest, EachBodyGetsItsPathAndItsDot) {
  FrameState state = state_of(builtin("stack"));
  BodyPaths paths;
  FrameState a = state;
  paths.add(&a, 0.01);
  ASSERT_EQ(a.overlays.size(), 4u);  // per body: the path and the dot
  EXPECT_EQ(a.overlays[0].points.size(), 1u);
  EXPECT_TRUE(a.overlays[0].segments.empty());
  FrameState b = state;
  for (Eigen::Index i = 0; i < b.x.size(); i += 2) b.x[i] += 0.1;  // every node 0.1 m right
  paths.add(&b, 0.01);
  ASSERT_EQ(b.overlays.size(), 4u);
  EXPECT_EQ(b.overlays[2].points.size(), 2u);
  EXPECT_EQ(b.overlays[2].segments.size(), 1u);
  EXPECT_NEAR((b.overlays[2].points[1] - b.overlays[2].points[0]).x(), 0.1, 1e-12);
  EXPECT_EQ(b.overlays[3].dot_radius, 0.01);
  EXPECT_FALSE(paths_by_default(builtin("compress")));
  EXPECT_TRUE(paths_by_default(builtin("stack-friction")));
}

// The point of the course's chapter 8, by data: where the top square slides off the
// bottom one, friction between them drags the bottom one along; without it the bottom
// one stays. The paths draw exactly this displacement (the bottom body's centroid), at
// the scenes' own mesh and at the mesh `invfree render` draws them with (n_seg 16).
TEST(BodyPathsTest, FrictionBetweenBodiesDragsTheBottomSquare) {
  for (const int n_seg : {2, 16}) {
    double drift[2] = {0.0, 0.0};
    int k = 0;
    for (const char* name : {"stack", "stack-friction"}) {
      SceneDef s = builtin(name);
      ASSERT_EQ(apply_override(s, "mesh.n_seg=" + std::to_string(n_seg)), "");
      Simulation sim = make_simulation(s);
      const Vec2 start = BodyPaths::centroids(capture_frame_state(sim))[1];
      double most = 0.0;
      for (int i = 0; i < 250; ++i) {
        ASSERT_EQ(step(sim).status, StepStatus::Ok) << name << " step " << i + 1;
        const Vec2 now = BodyPaths::centroids(capture_frame_state(sim))[1];
        most = std::max(most, std::abs(now.x() - start.x()));
      }
      drift[k++] = most;
    }
    // Measured: 0.04 and 0.5 m at n_seg 2, 0.02 and 0.17 m at n_seg 16.
    EXPECT_LT(drift[0], 0.06) << "stack, n_seg " << n_seg;
    EXPECT_GT(drift[1], 0.12) << "stack-friction, n_seg " << n_seg;
    EXPECT_GT(drift[1], 3.0 * drift[0]) << "n_seg " << n_seg;
  }
}

}  // namespace
}  // namespace invfree::render
