// The live window's inspector under Xvfb, with mouse and keys injected into ImGui as a
// person's would arrive: a click at a triangle's centroid inspects exactly that triangle and
// the Inspector shows the core's analysis of it at that step; Esc, a click on empty space and
// a mesh rebuild release it; a drag selects nothing; the colouring changes the picture; and
// goldens of the inspector with the stress colouring and of the psi colouring with glyphs.
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "app/live/live_app.h"
#include "app/live/mouse_gestures.h"
#include "scene_io/builtin_scenes.h"
#include "tests/render/image_compare.h"
#include "tests/run_command.h"
#include "tests/test_paths.h"
#include "triangle_fields.h"

namespace invfree::live {
namespace {

const std::string kGoldenDir = std::string(::invfree::test::source_dir()) + "/tests/live/goldens";

std::string temp_dir() {
  const std::string d = ::testing::TempDir() + "/live_inspector_" + std::to_string(::getpid());
  std::filesystem::create_directories(d);
  return d;
}

test::RgbImage rgb(const Image& img) {
  test::RgbImage out;
  out.width = img.width;
  out.height = img.height;
  out.rgb.reserve(static_cast<size_t>(img.width) * img.height * 3);
  for (size_t i = 0; i < img.rgba.size(); i += 4)
    out.rgb.insert(out.rgb.end(), {img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]});
  return out;
}

long differing_pixels(const Image& a, const Image& b) {
  const test::ImageDiff d = test::compare_images(rgb(a), rgb(b));
  return d.same_size ? d.differing : -1;
}

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

// A meshed shape (issue 27): the ring, dropped and resting on the ground, paused. A click
// at the centroid of a triangle in the ring's left wall inspects exactly that triangle with
// the core's values; a click in the hole, inside the ring's outline but on no triangle,
// selects nothing.
TEST(LiveInspector, PicksATriangleOfTheMeshedRing) {
  LiveOptions o;
  o.scenes = {{"ring", *load_builtin_scene("ring").scene},
              {"compress", *load_builtin_scene("compress").scene}};
  o.paused = true;
  o.vsync = false;
  std::string error;
  auto app = LiveApp::create(o, &error);
  ASSERT_TRUE(app) << error;
  for (int k = 0; k < 60; ++k) ASSERT_TRUE(app->controller().step_once());
  show(*app);
  const Simulation& sim = app->controller().simulation();
  Vec2 lo = sim.x.segment<2>(0), hi = lo;
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    lo = lo.cwiseMin(sim.x.segment<2>(2 * i));
    hi = hi.cwiseMax(sim.x.segment<2>(2 * i));
  }
  const Vec2 mid = 0.5 * (lo + hi);
  // The wall is 0.2 m thick of the ring's 1 m: a tenth of the way in is inside it.
  const std::optional<int> wall = triangle_at(sim, Vec2(lo.x() + 0.1 * (hi.x() - lo.x()), mid.y()));
  ASSERT_TRUE(wall.has_value());
  ASSERT_FALSE(triangle_at(sim, mid).has_value());  // the hole

  click(*app, app->to_window(mid));
  EXPECT_EQ(app->inspected(), nullptr);
  click(*app, app->to_window(centroid(sim, *wall)));
  const Inspected* in = app->inspected();
  ASSERT_NE(in, nullptr);
  EXPECT_EQ(in->triangle, *wall);
  EXPECT_EQ(in->step, 60);
  ASSERT_TRUE(in->elastic);
  const StressAnalysis expected = analyze_triangle(sim, *wall);
  EXPECT_EQ(in->analysis.F, expected.F);
  EXPECT_EQ(in->analysis.J, expected.J);
  EXPECT_EQ(in->analysis.cauchy, expected.cauchy);
  EXPECT_EQ(in->analysis.eigenvalues, expected.eigenvalues);
  EXPECT_GT(in->analysis.J, 0.0);
}

// Particles without triangles (the course's chapter 0) in the live window: the picture
// shows them (blue dots), every colouring, the glyphs and the landscape's window run, a
// click on the particle finds no triangle (an empty click), and asking for a triangle
// selects none.
TEST(LiveInspector, ParticlesHaveNoTriangleToPick) {
  for (const std::string name : {"course-0-spring", "course-0-free-fall"}) {
    LiveOptions o;
    o.scenes = {{name, *load_builtin_scene(name).scene},
                {"compress", *load_builtin_scene("compress").scene}};
    o.paused = true;
    o.vsync = false;
    o.show_landscape = true;
    o.stress_glyphs = true;
    std::string error;
    auto app = LiveApp::create(o, &error);
    ASSERT_TRUE(app) << error;
    for (int k = 0; k < 10; ++k) ASSERT_TRUE(app->controller().step_once());
    for (const TriangleField field :
         {TriangleField::DetF, TriangleField::Psi, TriangleField::Stress, TriangleField::Clamped}) {
      app->set_color_by(field);
      Image picture;
      app->frame(nullptr, &picture);
      long blue = 0;
      for (size_t i = 0; i + 3 < picture.rgba.size(); i += 4)
        blue += picture.rgba[i + 2] > 150 && picture.rgba[i] < 80 && picture.rgba[i + 1] < 110;
      EXPECT_GT(blue, 20) << name << " " << enum_name(kTriangleFieldNames, field);
    }
    const Simulation& sim = app->controller().simulation();
    ASSERT_EQ(sim.mesh.triangle_count(), 0);
    const int last = sim.mesh.node_count() - 1;
    click(*app, app->to_window(sim.x.segment<2>(2 * last)));
    EXPECT_EQ(app->inspected(), nullptr) << name;
    EXPECT_EQ(app->empty_clicks(), 1) << name;
    app->select_triangle(0);
    EXPECT_EQ(app->inspected(), nullptr) << name;
    show(*app);
  }
}

TEST(LiveInspector, EscReleasesAndNeverQuits) {
  auto app = open_compress(0);
  ASSERT_TRUE(app);
  app->select_triangle(5);
  show(*app);
  ASSERT_NE(app->inspected(), nullptr);
  press_key(*app, GLFW_KEY_ESCAPE);
  EXPECT_EQ(app->inspected(), nullptr);
  EXPECT_FALSE(app->should_close());
  press_key(*app, GLFW_KEY_ESCAPE);
  EXPECT_FALSE(app->should_close());  // issue 32: a second Esc quit, losing the settings
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

TEST(LiveInspector, TheColouringChangesThePicture) {
  auto app = open_compress(120);
  ASSERT_TRUE(app);
  EXPECT_EQ(app->color_by(), TriangleField::DetF);  // the default
  Image det_f, stress, psi;
  app->frame(nullptr, &det_f);
  app->set_color_by(TriangleField::Stress);
  app->frame(nullptr, &stress);
  app->set_color_by(TriangleField::Psi);
  app->frame(nullptr, &psi);
  EXPECT_GT(differing_pixels(det_f, stress), 5000);
  EXPECT_GT(differing_pixels(stress, psi), 5000);
}

// The numbers of `key`'s value in the JSON text `json` (a number, or arrays of them, read
// in order; `inspect --json` writes each number so that it reads back to the same double).
std::vector<double> numbers_of(const std::string& json, const std::string& key) {
  std::vector<double> out;
  size_t i = json.find("\"" + key + "\":");
  if (i == std::string::npos) return out;
  i += key.size() + 3;
  int depth = 0;
  for (; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '[' || c == '{') ++depth;
    if (c == ']' || c == '}') --depth;
    if (depth < 0 || (depth == 0 && (c == ',' || c == '\n'))) break;
    if ((c >= '0' && c <= '9') || c == '-') {
      char* end = nullptr;
      out.push_back(std::strtod(json.c_str() + i, &end));
      i = static_cast<size_t>(end - json.c_str()) - 1;
    }
  }
  return out;
}

std::vector<double> row_major(const Mat2& m) {
  return {m(0, 0), m(0, 1), m(1, 0), m(1, 1)};
}
std::vector<double> values(const auto& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

TEST(LiveInspector, ShowsWhatInspectReports) {
  // The Inspector 120 steps into compress, for the triangle clicked, against
  // `invfree inspect --step 120 --triangle T --json` in its own process: the same numbers.
  auto app = open_compress(120);
  ASSERT_TRUE(app);
  const int t = probe_triangle(app->controller().simulation());
  click(*app, app->to_window(centroid(app->controller().simulation(), t)));
  const Inspected* in = app->inspected();
  ASSERT_NE(in, nullptr);
  ASSERT_EQ(in->triangle, t);
  ASSERT_EQ(in->step, 120);
  const test::CommandResult r = test::run_command(
      ::invfree::test::exe_path(),
      "inspect --scene compress --step 120 --json --triangle " + std::to_string(t), true);
  ASSERT_EQ(r.code, 0) << r.err;
  const StressAnalysis& a = in->analysis;
  EXPECT_EQ(numbers_of(r.out, "triangle"), std::vector<double>{double(t)});
  EXPECT_EQ(numbers_of(r.out, "mu"), std::vector<double>{a.lame.mu});
  EXPECT_EQ(numbers_of(r.out, "lambda"), std::vector<double>{a.lame.lambda});
  EXPECT_EQ(numbers_of(r.out, "F"), row_major(a.F));
  EXPECT_EQ(numbers_of(r.out, "U"), row_major(a.svd.U));
  EXPECT_EQ(numbers_of(r.out, "sigma"), values(a.svd.sigma));
  EXPECT_EQ(numbers_of(r.out, "V"), row_major(a.svd.V));
  EXPECT_EQ(numbers_of(r.out, "J"), std::vector<double>{a.J});
  EXPECT_EQ(numbers_of(r.out, "psi"), std::vector<double>{a.psi});
  EXPECT_EQ(numbers_of(r.out, "P"), row_major(a.P));
  EXPECT_EQ(numbers_of(r.out, "cauchy"), row_major(a.cauchy));
  EXPECT_EQ(numbers_of(r.out, "values"), values(a.principal_stress));
  EXPECT_EQ(numbers_of(r.out, "eigenvalues"), values(a.eigenvalues));
  EXPECT_EQ(numbers_of(r.out, "projected_eigenvalues"), values(a.projected_eigenvalues));
  EXPECT_EQ(numbers_of(r.out, "clamped"), std::vector<double>{double(a.clamped)});
  EXPECT_EQ(numbers_of(r.out, "fd_error_P"), std::vector<double>{in->fd.P});
  EXPECT_EQ(numbers_of(r.out, "fd_error_dPdF"), std::vector<double>{in->fd.dPdF});
}

int run(const std::string& args) {
  const std::string cmd = std::string(::invfree::test::exe_path()) + " " + args + " >/dev/null";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void expect_golden(const std::string& args, const std::string& name) {
  const std::string png = temp_dir() + "/" + name + ".png";
  ASSERT_EQ(run("live " + args + " --force --screenshot " + png), 0) << args;
  test::RgbImage actual;
  ASSERT_TRUE(test::load_png(png, &actual)) << png;
  const std::string e = test::check_golden(actual, name, kGoldenDir, temp_dir());
  EXPECT_TRUE(e.empty()) << e;
}

TEST(LiveInspector, InspectorAndStressColouringMatchGolden) {
  // 1.2 s into compress, the ceiling pressing: a triangle right of the middle, near the top,
  // inspected (outlined; the Inspector on the picture's left, away from it; its twist
  // eigenvalue negative and clamped), coloured by principal stress.
  expect_golden("--scene compress --frames 120 --select-triangle 21 --color-by stress",
                "live_inspector_stress");
}

TEST(LiveInspector, PsiColouringWithGlyphsMatchesGolden) {
  // The same moment without the panel: psi on its log scale and the principal-stress glyphs.
  expect_golden("--scene compress --frames 120 --no-panel --color-by psi --stress-glyphs",
                "live_psi_glyphs");
}

}  // namespace
}  // namespace invfree::live
