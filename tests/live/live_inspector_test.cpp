// The live window's inspector under Xvfb, with mouse and keys injected into ImGui as a
// person's would arrive: a click at a triangle's centroid inspects exactly that triangle and
// the Inspector shows the core's analysis of it at that step; Esc, a click on empty space and
// a mesh rebuild release it; a drag selects nothing.
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include "app/live/live_app.h"
#include "app/live/mouse_gestures.h"
#include "scene_io/builtin_scenes.h"
#include "triangle_fields.h"

namespace invfree::live {
namespace {

// One frame with the pointer resting on the panel's corner: a frame that is drawn even
// while paused and idle (a frame without input then waits for some and draws nothing).
void show(LiveApp& app) {
  Injection in;
  in.x = in.y = 3.0f;
  app.frame(&in);
}

// The compress scene `steps` steps in, paused (the state holds still between frames).
std::unique_ptr<LiveApp> open_compress(int steps) {
  LiveOptions o;
  o.scenes = {{"compress", *load_builtin_scene("compress").scene},
              {"drop", *load_builtin_scene("drop").scene}};
  o.paused = true;
  o.vsync = false;
  std::string error;
  auto app = LiveApp::create(o, &error);
  EXPECT_TRUE(app) << error;
  if (!app) return app;
  for (int k = 0; k < steps; ++k) EXPECT_TRUE(app->controller().step_once());
  show(*app);
  return app;
}

Vec2 centroid(const Simulation& sim, int t) {
  Vec2 c = Vec2::Zero();
  for (int node : sim.mesh.triangles[static_cast<size_t>(t)]) c += sim.x.segment<2>(2 * node);
  return c / 3.0;
}

// A left click at window point p: hover, press, release (a frame each), then one more frame
// to settle; `move` is added to the pointer between the press and the release (a drag).
void click(LiveApp& app, const Vec2& p, const Vec2& move = Vec2::Zero()) {
  Injection in;
  in.x = static_cast<float>(p.x());
  in.y = static_cast<float>(p.y());
  app.frame(&in);
  in.down[0] = true;
  app.frame(&in);
  in.x += static_cast<float>(move.x());
  in.y += static_cast<float>(move.y());
  app.frame(&in);
  in.down[0] = false;
  app.frame(&in);
  app.frame(&in);
}

void press_key(LiveApp& app, int key) {
  Injection in;
  in.x = in.y = 3.0f;  // on the panel's corner: no gesture
  in.keys = {key};
  app.frame(&in);
  Injection up;
  up.x = up.y = 3.0f;
  app.frame(&up);
}

// The triangle at the body's horizontal middle, three quarters up (below the ceiling).
int probe_triangle(const Simulation& sim) {
  Vec2 lo = sim.x.segment<2>(0), hi = lo;
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    lo = lo.cwiseMin(sim.x.segment<2>(2 * i));
    hi = hi.cwiseMax(sim.x.segment<2>(2 * i));
  }
  const std::optional<int> t =
      triangle_at(sim, Vec2(0.5 * (lo.x() + hi.x()) + 1e-3, lo.y() + 0.75 * (hi.y() - lo.y())));
  EXPECT_TRUE(t.has_value());
  return t.value_or(0);
}

// A point on the picture beside the body at its mid-height (left or right of it, where no
// window lies: the inspector goes to the side away from its triangle), on no triangle.
Vec2 empty_point(LiveApp& app) {
  const Simulation& sim = app.controller().simulation();
  double x_min = 1e9, x_max = -1e9, y_sum = 0.0;
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    x_min = std::min(x_min, sim.x(2 * i));
    x_max = std::max(x_max, sim.x(2 * i));
    y_sum += sim.x(2 * i + 1);
  }
  const double y = y_sum / sim.mesh.node_count();
  const auto& rects = app.widget_rects();
  const auto covered = [&](const Vec2& p) {
    for (const auto& [name, r] : rects)
      if (p.x() >= r.x0 - 10 && p.x() <= r.x1 + 10 && p.y() >= r.y0 - 10 && p.y() <= r.y1 + 10)
        return true;
    return p.x() <= rects.at("mu").x1 + 10.0;  // the panel (its rows end before its edge)
  };
  for (const Vec2& w : {Vec2(x_min - 0.25, y), Vec2(x_max + 0.25, y)}) {
    const Vec2 p = app.to_window(w);
    if (!covered(p) && !triangle_at(sim, w)) return p;
  }
  ADD_FAILURE() << "no empty point beside the body";
  return Vec2::Zero();
}

TEST(LiveInspector, AClickAtATrianglesCentroidInspectsItWithTheCoresValues) {
  auto app = open_compress(120);
  ASSERT_TRUE(app);
  EXPECT_EQ(app->inspected(), nullptr);
  const int t = probe_triangle(app->controller().simulation());
  click(*app, app->to_window(centroid(app->controller().simulation(), t)));
  const Inspected* in = app->inspected();
  ASSERT_NE(in, nullptr);
  EXPECT_EQ(in->triangle, t);
  const Simulation& sim = app->controller().simulation();
  EXPECT_EQ(in->step, sim.step_count);
  EXPECT_EQ(in->step, 120);
  ASSERT_TRUE(in->elastic);
  const StressAnalysis expected = analyze_triangle(sim, t);
  EXPECT_EQ(in->analysis.F, expected.F);
  EXPECT_EQ(in->analysis.svd.U, expected.svd.U);
  EXPECT_EQ(in->analysis.svd.sigma, expected.svd.sigma);
  EXPECT_EQ(in->analysis.svd.V, expected.svd.V);
  EXPECT_EQ(in->analysis.J, expected.J);
  EXPECT_EQ(in->analysis.psi, expected.psi);
  EXPECT_EQ(in->analysis.P, expected.P);
  EXPECT_EQ(in->analysis.cauchy, expected.cauchy);
  EXPECT_EQ(in->analysis.principal_stress, expected.principal_stress);
  EXPECT_EQ(in->analysis.eigenvalues, expected.eigenvalues);
  EXPECT_EQ(in->analysis.projected_eigenvalues, expected.projected_eigenvalues);
  EXPECT_EQ(in->analysis.clamped, expected.clamped);
  EXPECT_EQ(in->fd.P, finite_difference_errors(expected.model, expected.F, expected.lame).P);
  EXPECT_NE(expected.F, Mat2::Identity());  // the ceiling presses: a deformed triangle
  EXPECT_TRUE(app->widget_rects().count("inspector"));

  // Played on, the values follow the state: after three more steps (paused again, one
  // frame to show it) they are the analysis of step 123.
  app->controller().set_playing(true);
  for (int k = 0; k < 3; ++k) show(*app);
  app->controller().set_playing(false);
  show(*app);
  in = app->inspected();
  ASSERT_NE(in, nullptr);
  EXPECT_EQ(in->step, 123);
  EXPECT_EQ(in->analysis.F, analyze_triangle(app->controller().simulation(), t).F);
  EXPECT_NE(in->analysis.F, expected.F);
}

TEST(LiveInspector, EscReleasesThenQuits) {
  auto app = open_compress(0);
  ASSERT_TRUE(app);
  app->select_triangle(5);
  show(*app);
  ASSERT_NE(app->inspected(), nullptr);
  press_key(*app, GLFW_KEY_ESCAPE);
  EXPECT_EQ(app->inspected(), nullptr);
  EXPECT_FALSE(app->should_close());
  press_key(*app, GLFW_KEY_ESCAPE);
  EXPECT_TRUE(app->should_close());
}

TEST(LiveInspector, AClickOnEmptySpaceReleases) {
  auto app = open_compress(0);
  ASSERT_TRUE(app);
  const int t = probe_triangle(app->controller().simulation());
  click(*app, app->to_window(centroid(app->controller().simulation(), t)));
  ASSERT_NE(app->inspected(), nullptr);
  const Vec2 empty = empty_point(*app);
  click(*app, empty);
  EXPECT_EQ(app->inspected(), nullptr);
  EXPECT_EQ(app->empty_clicks(), 0);  // that click released: not an empty click
  click(*app, empty);
  EXPECT_EQ(app->empty_clicks(), 1);  // nothing to release: counted (the web page's tap)
  EXPECT_EQ(app->inspected(), nullptr);
}

TEST(LiveInspector, ADragSelectsNothing) {
  auto app = open_compress(0);
  ASSERT_TRUE(app);
  const int t = probe_triangle(app->controller().simulation());
  const Vec2 p = app->to_window(centroid(app->controller().simulation(), t));
  click(*app, p, Vec2(40.0, 0.0));  // a pull (or a pan) 40 pixels to the right
  EXPECT_EQ(app->inspected(), nullptr);
  EXPECT_EQ(app->empty_clicks(), 0);
  // A press that wanders less than the click slop is still a click (where the triangle is
  // now: the drag may have panned the view).
  click(*app, app->to_window(centroid(app->controller().simulation(), t)),
        Vec2(0.5 * kClickSlop, 0.0));
  ASSERT_NE(app->inspected(), nullptr);
  EXPECT_EQ(app->inspected()->triangle, t);
}

TEST(LiveInspector, AMeshRebuildReleases) {
  auto app = open_compress(0);
  ASSERT_TRUE(app);
  app->select_triangle(7);
  show(*app);
  ASSERT_NE(app->inspected(), nullptr);
  SceneDef finer = app->controller().settings();
  finer.n_seg += 2;
  ASSERT_TRUE(app->controller().apply(finer));
  show(*app);
  EXPECT_EQ(app->inspected(), nullptr);
  app->select_triangle(7);
  show(*app);
  ASSERT_NE(app->inspected(), nullptr);
  app->controller().select_scene(1);
  show(*app);
  EXPECT_EQ(app->inspected(), nullptr);
}

}  // namespace
}  // namespace invfree::live
