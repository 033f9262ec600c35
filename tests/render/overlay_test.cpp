// Overlays and frames without triangles, without GL: the particles' dot size, the
// overlay's points and springs, the panel's words for particles (no det F, no NaN), and the
// camera of particles (a lone one has a rest box of no size).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/render/camera.h"
#include "app/render/frame_vertices.h"
#include "app/render/renderer.h"
#include "app/render/text_atlas.h"
#include "scene/scene.h"

namespace invfree::render {
namespace {

TEST(Overlay, ParticleDotsScaleWithTheSpringsAndAreAtMostTheTutorials) {
  // The tutorial's simulator2: 0.25 m springs, dots of 0.02 m; here a tenth of the median.
  const std::vector<Vec2> rest = {{0, 0}, {0.25, 0}, {0.25, 0.25}, {0, 0.25}};
  EXPECT_NEAR(particle_dot_radius(rest, {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}}), 0.025, 1e-15);
  EXPECT_EQ(particle_dot_radius({{0, 0}}, {}), 0.1);                        // alone
  EXPECT_EQ(particle_dot_radius({{0, 0}, {5, 0}}, {{0, 1}}), 0.1);          // long spring
  EXPECT_EQ(particle_dot_radius({{0, 0}, {0, 0}}, {{0, 1}, {0, 7}}), 0.1);  // no usable one
}

TEST(Overlay, ParticleOverlayHasEveryNodeAndTheValidSprings) {
  VecX x(6);
  x << 0, 1, 2, 3, 4, 5;
  const Overlay o = particle_overlay(x, {{0, 1}, {1, 2}, {2, 3}, {1, 1}, {-1, 0}}, 0.05);
  ASSERT_EQ(o.points.size(), 3u);
  EXPECT_EQ(o.points[2], Vec2(4, 5));
  EXPECT_EQ(o.segments, (std::vector<std::array<int, 2>>{{0, 1}, {1, 2}}));
  EXPECT_EQ(o.dot_radius, 0.05);
  const Overlay a = anchor_overlay({Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)}, 0.1);
  EXPECT_EQ(a.segments.size(), 3u);
  EXPECT_NEAR(a.dot_radius, 0.02, 1e-15);  // twice the tutorial's 0.1 side / n_seg
}

// The words a frame of `state` puts on the panel.
std::vector<std::string> panel_words(const FrameState& state, const DrawOptions& options = {}) {
  static TextAtlas atlas;
  FrameVertices v;
  v.font_sizes = {31, 21, 18};
  if (atlas.width() == 0) atlas.build(v.font_sizes);
  v.atlas = &atlas;
  const FrameLayout L = frame_layout(1280, 720);
  build_frame_vertices(v, state, L, scene_camera(state.scene, L), options);
  for (const ShapeVertex& p : v.shapes) {
    EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
    if (!(std::isfinite(p.x) && std::isfinite(p.y))) break;
  }
  return v.words;
}

bool has(const std::vector<std::string>& words, const std::string& w) {
  return std::find(words.begin(), words.end(), w) != words.end();
}

FrameState particles(int n) {
  FrameState f;
  f.scene.name = "particles";
  f.scene.has_mass_spring = true;
  f.scene.shape.kind = ShapeKind::Points;
  f.x = VecX::Zero(2 * n);
  std::vector<std::array<int, 2>> springs;
  for (int i = 0; i < n; ++i) {
    f.x[2 * i] = 0.3 * i;
    f.scene.shape.points.emplace_back(0.3 * i, 0.0);
    if (i > 0) springs.push_back({i - 1, i});
  }
  f.overlays.push_back(particle_overlay(f.x, springs, 0.03));
  return f;
}

TEST(Overlay, PanelOfParticlesSaysNoTrianglesAndHasNoNumbersOfNone) {
  for (const TriangleField field :
       {TriangleField::DetF, TriangleField::Psi, TriangleField::Stress, TriangleField::Clamped}) {
    FrameState f = particles(3);
    f.color_by = field;
    const std::vector<std::string> words = panel_words(f);
    EXPECT_TRUE(has(words, "no triangles"));
    EXPECT_TRUE(has(words, "3 particles"));
    EXPECT_TRUE(has(words, "2 springs"));
    for (const std::string& w : words) {
      EXPECT_EQ(w.find("det F"), std::string::npos) << w;
      EXPECT_EQ(w.find("nan"), std::string::npos) << w;
      EXPECT_EQ(w.find("inf"), std::string::npos) << w;
    }
  }
  const std::vector<std::string> one = panel_words(particles(1));
  EXPECT_TRUE(has(one, "1 particle"));
  EXPECT_FALSE(has(one, "0 springs"));
  // A particle without springs has no stiffness to show (the free fall's [mass_spring]
  // only stands in for the elasticity it does not have).
  EXPECT_TRUE(has(one, "particles"));
  EXPECT_FALSE(has(one, "mass-spring"));
  EXPECT_TRUE(has(panel_words(particles(2)), "mass-spring"));
}

TEST(Overlay, PanelOfTrianglesIsUnchanged) {
  // A frame with triangles keeps its det F lines and bar.
  FrameState f;
  f.x.resize(6);
  f.x << 0, 0, 1, 0, 0, 1;
  f.triangles = {{0, 1, 2}};
  f.det_f = {1.0};
  f.field = f.det_f;
  const std::vector<std::string> words = panel_words(f);
  EXPECT_TRUE(has(words, "min det F = 1.000"));
  EXPECT_FALSE(has(words, "no triangles"));
}

TEST(Overlay, ParticlesAreFramedWithRoomAround) {
  SceneDef s;
  s.has_ground = s.has_ceiling = false;
  s.shape.kind = ShapeKind::Points;
  s.shape.points = {Vec2(0.2, 0.1)};  // alone: a box of no size
  WorldBox b = scene_world_box(s);
  EXPECT_LE(b.x0, 0.2 - kParticleReach);
  EXPECT_GE(b.x1, 0.2 + kParticleReach);
  EXPECT_LE(b.y0, 0.1 - kParticleReach);
  EXPECT_GE(b.y1, 0.1 + kParticleReach);
  const Camera c = fit_camera(b, {0, 0, 990, 720});
  EXPECT_TRUE(std::isfinite(c.pixels_per_metre) && c.pixels_per_metre > 0.0);
  // A chain 3 m long: half its size around it.
  s.shape.points = {Vec2(0, 0), Vec2(3, 0)};
  b = scene_world_box(s);
  EXPECT_LE(b.x0, -1.5);
  EXPECT_GE(b.x1, 4.5);
  // With a ground below: it is in the picture.
  s.has_ground = true;
  s.ground_y = -2.0;
  EXPECT_LT(scene_world_box(s).y0, -2.0);
  // A box of no size at all is widened, not divided by.
  const Camera z = fit_camera({1, 1, 2, 2}, {0, 0, 100, 100});
  EXPECT_TRUE(std::isfinite(z.pixels_per_metre));
  EXPECT_NEAR(z.to_pixel(Vec2(1, 2)).x(), 50.0, 1e-9);
}

}  // namespace
}  // namespace invfree::render
