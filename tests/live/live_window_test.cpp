// The live window under a real X server (Xvfb, started by xvfb-run: see
// tests/live/CMakeLists.txt) with Mesa's software OpenGL:
//  - `invfree live --frames N --screenshot FILE` against goldens (the rule of the
//    offscreen goldens, tests/render/image_compare.h);
//  - the mu slider dragged with mouse input injected into ImGui changes the simulation's
//    mu and the picture;
//  - grabbing a node with the mouse pulls it toward the cursor, and only while dragging;
//  - the keyboard table drives play/pause and the panel.
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string_view>
#include <tuple>

#include "app/live/live_app.h"
#include "scene_io/builtin_scenes.h"
#include "tests/render/image_compare.h"
#include "tests/test_paths.h"

namespace invfree::live {
namespace {

const std::string kGoldenDir = std::string(::invfree::test::source_dir()) + "/tests/live/goldens";

std::string temp_dir() {
  const std::string d = ::testing::TempDir() + "/live_window_" + std::to_string(::getpid());
  std::filesystem::create_directories(d);
  return d;
}

int run(const std::string& args) {
  const std::string cmd = std::string(::invfree::test::exe_path()) + " " + args + " >/dev/null";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
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

// The golden check of one `invfree live` run.
void expect_golden(const std::string& args, const std::string& name, int width = 1280,
                   int height = 720) {
  const std::string png = temp_dir() + "/" + name + ".png";
  ASSERT_EQ(run("live " + args + " --screenshot " + png), 0) << args;
  test::RgbImage actual;
  ASSERT_TRUE(test::load_png(png, &actual)) << png;
  EXPECT_EQ(actual.width, width);
  EXPECT_EQ(actual.height, height);
  const std::string e = test::check_golden(actual, name, kGoldenDir, temp_dir());
  EXPECT_TRUE(e.empty()) << e;
}

TEST(LiveWindow, RunningCompressionMatchesGolden) {
  // 120 frames = 1.2 s of the demo, one step per frame: the ceiling is pressing.
  expect_golden("--scene compress --frames 120 --no-panel", "live_compress_120");
}

TEST(LiveWindow, PausedPanelMatchesGolden) {
  // The panel, the PAUSED banner, a stiffer material from --set.
  expect_golden("--scene compress --set material.E=3e5 --frames 3 --paused", "live_panel_paused");
}

TEST(LiveWindow, LargeUiScaleMatchesGolden) {
  // The back-row layout: 1920x1080 at UI scale 1.5 (the default there), the det F panel
  // over the picture with the automatic colour range of the run so far, 1.2 s in.
  expect_golden(
      "--scene compress --frames 120 --size 1920x1080 --ui-scale 1.5 --det-f-panel over "
      "--color-range run",
      "live_ui_scale_1_5", 1920, 1080);
}

std::unique_ptr<LiveApp> open_app(LiveOptions o) {
  if (o.scenes.empty()) {
    // Every built-in scene, `compress` selected (the tests' values are its: the list is in
    // name order, and the shapes' `bunny` now comes first).
    for (const auto& e : builtin_scenes()) {
      if (e.name == std::string_view("compress")) o.selected = static_cast<int>(o.scenes.size());
      o.scenes.push_back({std::string(e.name), *load_builtin_scene(e.name).scene});
    }
  }
  o.vsync = false;
  std::string error;
  auto app = LiveApp::create(o, &error);
  EXPECT_TRUE(app) << error;
  return app;
}

long differing_pixels(const Image& a, const Image& b) {
  const test::ImageDiff d = test::compare_images(rgb(a), rgb(b));
  return d.same_size ? d.differing : -1;
}

TEST(LiveWindow, InjectedMouseDragsTheMuSlider) {
  LiveOptions o;
  o.paused = true;
  auto app = open_app(o);
  ASSERT_TRUE(app);
  Image before, after;
  app->frame(nullptr, &before);
  ASSERT_TRUE(app->widget_rects().count("mu"));
  const WidgetRect r = app->widget_rects().at("mu");
  const double mu0 = app->controller().simulation().scene.lame.mu;
  const float y = 0.5f * (r.y0 + r.y1);
  auto at = [&](float fraction, bool down) {
    Injection in;
    in.x = r.x0 + fraction * (r.x1 - r.x0);
    in.y = y;
    in.down[0] = down;
    return in;
  };
  // Hover, press, drag to the right, release: as a hand on the mouse would, frame by frame.
  const Injection script[] = {at(0.3f, false), at(0.3f, true),  at(0.6f, true),
                              at(0.9f, true),  at(0.9f, false), at(0.9f, false)};
  for (const Injection& in : script) app->frame(&in);
  app->frame(nullptr, &after);
  const double mu1 = app->controller().simulation().scene.lame.mu;
  // 90% of the way along the log scale from 1e2 to 1e7 Pa is about 3e6 Pa.
  EXPECT_GT(mu1, 1e6) << "mu was " << mu0;
  EXPECT_LT(mu1, 1e7);
  EXPECT_EQ(app->controller().simulation().scene.lame.lambda,
            app->controller().scenes()[app->controller().selected_scene()].scene.lame.lambda);
  // The picture changed: the slider, the side panel's mu, E and nu (paused: same shape).
  EXPECT_GT(differing_pixels(before, after), 100);

  // Played on, the stiffer square deforms less under gravity than the default one.
  app->controller().set_playing(true);
  for (int k = 0; k < 40; ++k) app->frame();
  const double stiff_min_det = app->controller().stats().min_det_f;
  LiveOptions o2;
  auto soft = open_app(o2);
  ASSERT_TRUE(soft);
  for (int k = 0; k < 40; ++k) soft->frame();
  EXPECT_GT(stiff_min_det, soft->controller().stats().min_det_f);
}

TEST(LiveWindow, KeysToggleThePanelAndPlayback) {
  LiveOptions o;
  o.paused = true;
  auto app = open_app(o);
  ASSERT_TRUE(app);
  app->frame();
  EXPECT_FALSE(app->widget_rects().empty());
  // Clicking the Play button with the mouse starts the simulation.
  const WidgetRect play = app->widget_rects().at("play");
  Injection in;
  in.x = 0.5f * (play.x0 + play.x1);
  in.y = 0.5f * (play.y0 + play.y1);
  app->frame(&in);
  in.down[0] = true;
  app->frame(&in);
  in.down[0] = false;
  app->frame(&in);
  EXPECT_TRUE(app->controller().playing());
  const long s = app->controller().simulation().step_count;
  app->frame(&in);
  EXPECT_EQ(app->controller().simulation().step_count, s + 1);
}

}  // namespace
}  // namespace invfree::live

namespace invfree::live {
namespace {

// Without --ui-scale the scale follows the window: 1 at 1280x720, 1.5 at 1920x1080.
TEST(LiveWindow, DefaultUiScaleFollowsTheWindowSize) {
  for (const auto& [w, h, scale] : {std::tuple{1280, 720, 1.0f}, std::tuple{1920, 1080, 1.5f}}) {
    LiveOptions o;
    o.width = w;
    o.height = h;
    auto app = open_app(o);
    ASSERT_TRUE(app);
    app->frame();
    EXPECT_FLOAT_EQ(app->view().ui_scale, scale) << w << "x" << h;
  }
}

TEST(LiveWindow, KeyboardShortcutsAct) {
  LiveOptions o;
  o.screenshot_dir = temp_dir();
  auto app = open_app(o);
  ASSERT_TRUE(app);
  auto press = [&](int key, bool ctrl = false, const char* text = "") {
    Injection in;
    in.keys = {key};
    in.ctrl = ctrl;
    in.text = text;
    app->frame(&in);
    Injection up;
    up.ctrl = ctrl;
    app->frame(&up);
  };
  app->frame();
  ASSERT_TRUE(app->controller().playing());
  press(GLFW_KEY_SPACE);
  EXPECT_FALSE(app->controller().playing());
  const long s = app->controller().simulation().step_count;
  press(GLFW_KEY_S);
  EXPECT_EQ(app->controller().simulation().step_count, s + 1);
  press(GLFW_KEY_R);
  EXPECT_EQ(app->controller().simulation().step_count, 0);
  EXPECT_FALSE(app->widget_rects().empty());
  press(GLFW_KEY_TAB);
  EXPECT_TRUE(app->widget_rects().empty());  // the panel is hidden
  press(GLFW_KEY_TAB);
  EXPECT_FALSE(app->widget_rects().empty());
  Image plain, help;
  app->frame(nullptr, &plain);
  press(GLFW_KEY_F1);
  app->frame(nullptr, &help);
  EXPECT_GT(differing_pixels(plain, help), 2000);  // the overlay appeared
  press(GLFW_KEY_P, true);
  ASSERT_FALSE(app->messages().empty());
  const std::string shot = o.screenshot_dir + "/invfree_0001.png";
  EXPECT_EQ(app->messages().back(), "screenshot: " + shot);
  test::RgbImage img;
  EXPECT_TRUE(test::load_png(shot, &img));
  // The view's keys: + and - (the characters typed) step the UI scale by 0.25 (within its
  // range), D cycles the det F panel beside / over / hidden, C the colour range fixed / run /
  // frame.
  const LiveApp::View v0 = app->view();
  press(GLFW_KEY_EQUAL, false, "=");
  EXPECT_FLOAT_EQ(app->view().ui_scale, std::min(kMaxUiScale, v0.ui_scale + 0.25f));
  press(GLFW_KEY_MINUS, false, "-");
  press(GLFW_KEY_MINUS, false, "-");
  EXPECT_FLOAT_EQ(app->view().ui_scale, std::max(kMinUiScale, v0.ui_scale - 0.25f));
  EXPECT_EQ(v0.det_f_panel, render::PanelMode::Side);
  for (render::PanelMode m :
       {render::PanelMode::Overlay, render::PanelMode::Hidden, render::PanelMode::Side}) {
    press(GLFW_KEY_D);
    EXPECT_EQ(app->view().det_f_panel, m);
  }
  EXPECT_EQ(v0.color_range, render::ColorRangeMode::Fixed);
  for (render::ColorRangeMode m : {render::ColorRangeMode::Run, render::ColorRangeMode::Frame,
                                   render::ColorRangeMode::Fixed}) {
    press(GLFW_KEY_C);
    EXPECT_EQ(app->view().color_range, m);
  }
  press(GLFW_KEY_P);  // plain P: presentation mode, no screenshot
  EXPECT_FALSE(std::filesystem::exists(o.screenshot_dir + "/invfree_0002.png"));
  EXPECT_TRUE(app->presenting());
  press(GLFW_KEY_P);
  EXPECT_FALSE(app->presenting());
  EXPECT_FALSE(app->should_close());
  press(GLFW_KEY_ESCAPE);  // the help overlay (F1 above) closes
  EXPECT_FALSE(app->should_close());
  press(GLFW_KEY_ESCAPE);  // nothing open: Esc says how to quit, and does not
  EXPECT_FALSE(app->should_close());
  EXPECT_NE(app->controller().note.find("Ctrl+Q"), std::string::npos) << app->controller().note;
  press(GLFW_KEY_Q);
  EXPECT_FALSE(app->should_close());
  press(GLFW_KEY_Q, true);
  EXPECT_TRUE(app->should_close());
}

TEST(LiveWindow, RecordingWritesTheRenderNaming) {
  LiveOptions o;
  o.record_dir = temp_dir() + "/rec";
  std::filesystem::remove_all(o.record_dir);
  {
    auto app = open_app(o);
    ASSERT_TRUE(app);
    for (int k = 0; k < 5; ++k) app->frame();
  }  // closing the window finishes the recording
  for (int k = 0; k < 5; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%06d.png", k);
    test::RgbImage img;
    EXPECT_TRUE(test::load_png(o.record_dir + name, &img)) << name;
    EXPECT_EQ(img.width, 1280);
  }
  EXPECT_FALSE(std::filesystem::exists(o.record_dir + "/frame_000005.png"));
}

}  // namespace
}  // namespace invfree::live

namespace invfree::live {
namespace {

TEST(LiveWindow, DraggingANodePullsItOnlyWhileHeld) {
  LiveOptions o;
  o.scenes = {{"drop", *load_builtin_scene("drop").scene}};
  auto app = open_app(o);
  ASSERT_TRUE(app);
  app->frame();
  const SceneDef& s = app->controller().settings();
  const int node = s.n_seg * (s.n_seg + 1) + s.n_seg;  // top right corner
  const Vec2 start = app->controller().simulation().x.segment<2>(2 * node);
  const Vec2 p = app->to_window(start);
  Injection in;
  in.x = static_cast<float>(p.x());
  in.y = static_cast<float>(p.y());
  app->frame(&in);  // hover
  in.down[0] = true;
  app->frame(&in);  // press on the node: grabbed
  ASSERT_TRUE(app->controller().pulling());
  EXPECT_EQ(app->controller().pull_node(), node);
  in.x += 120.0f;  // drag up and to the right, and hold there
  in.y -= 160.0f;
  for (int k = 0; k < 40; ++k) app->frame(&in);
  const Vec2 target = app->controller().pull_target();
  const Vec2 now = app->controller().simulation().x.segment<2>(2 * node);
  // Held up against gravity by the spring, close to the cursor (the default stiffness
  // lets the square's weight stretch it by about a tenth of a metre).
  EXPECT_LT((now - target).norm(), 0.5 * (start - target).norm())
      << now.transpose() << " " << target.transpose();
  EXPECT_GT(now.x(), start.x());
  EXPECT_GT(now.y(), start.y());
  in.down[0] = false;
  app->frame(&in);
  EXPECT_FALSE(app->controller().pulling());
  EXPECT_FALSE(app->controller().simulation().pull.on);
}

TEST(LiveWindow, WheelZoomsAndFFramesTheBodies) {
  LiveOptions o;
  o.paused = true;
  o.hide_panel = true;
  auto app = open_app(o);
  ASSERT_TRUE(app);
  Image stage, framed, zoomed, panned, back;
  app->frame(nullptr, &stage);
  Injection f;
  f.keys = {GLFW_KEY_F};
  app->frame(&f);
  app->frame(nullptr, &framed);
  // F frames the bodies (every node), closer than the whole stage: the square grows.
  const Vec2 c0 = app->to_window(Vec2(-0.5, -0.5)), c1 = app->to_window(Vec2(0.5, 0.5));
  EXPECT_GT(differing_pixels(stage, framed), 20000);
  EXPECT_GT(c1.x() - c0.x(), 400.0);  // the 1 m square, in window pixels (720 high)
  Injection in;
  in.x = 500;
  in.y = 400;
  in.wheel = 3.0f;
  app->frame(&in, &zoomed);
  EXPECT_GT(differing_pixels(framed, zoomed), 20000);
  Injection drag;
  drag.x = 500;
  drag.y = 400;
  drag.down[1] = true;  // right-drag pans
  app->frame(&drag);
  drag.x += 80;
  app->frame(&drag);
  drag.down[1] = false;
  app->frame(&drag, &panned);
  EXPECT_GT(differing_pixels(zoomed, panned),
            2000);  // the square moved (the hatching is fixed to the screen)
  app->frame(&f);
  app->frame(nullptr, &back);
  EXPECT_TRUE(test::compare_images(rgb(back), rgb(framed)).matches());
}

}  // namespace
}  // namespace invfree::live

namespace invfree::live {
namespace {

// Types `text` into the panel field `name` (click, Ctrl+A, characters, Enter).
void type_into(LiveApp& app, const std::string& name, const std::string& text) {
  const WidgetRect r = app.widget_rects().at(name);
  Injection in;
  in.x = 0.5f * (r.x0 + r.x1);
  in.y = 0.5f * (r.y0 + r.y1);
  app.frame(&in);
  in.down[0] = true;
  app.frame(&in);
  in.down[0] = false;
  app.frame(&in);
  Injection select = in;
  select.keys = {GLFW_KEY_A};
  select.ctrl = true;
  app.frame(&select);
  Injection typed = in;
  typed.text = text;
  app.frame(&typed);
  Injection enter = in;
  enter.keys = {GLFW_KEY_ENTER};
  app.frame(&enter);
  app.frame(&in);
}

TEST(LiveWindow, APulledBodyStaysOutOfThePanels) {
  // Dragging a node over the ImGui panel (left) or the det F panel (right): the spring's
  // target stops at the visible picture's edge, so the body cannot slide behind a panel.
  LiveOptions o;
  o.paused = true;
  auto app = open_app(o);
  ASSERT_TRUE(app);
  app->frame();
  const float panel_right = app->widget_rects().at("mu").x1;  // inside the ImGui panel
  const SceneDef& s = app->controller().settings();
  const int node = s.n_seg * (s.n_seg + 1);  // top left corner
  const Vec2 p = app->to_window(app->controller().simulation().x.segment<2>(2 * node));
  Injection in;
  in.x = static_cast<float>(p.x());
  in.y = static_cast<float>(p.y());
  app->frame(&in);
  in.down[0] = true;
  app->frame(&in);
  ASSERT_TRUE(app->controller().pulling());
  in.x = 20.0f;  // far into the ImGui panel
  app->frame(&in);
  EXPECT_GT(app->to_window(app->controller().pull_target()).x(), panel_right);
  in.x = 1270.0f;  // into the det F panel (the right 290 pixels at 1280x720)
  app->frame(&in);
  EXPECT_LT(app->to_window(app->controller().pull_target()).x(), 1280.0 - 290.0);
  in.down[0] = false;
  app->frame(&in);
}

TEST(LiveWindow, NoHoverRingUntilThePointerMoves) {
  // A pointer resting on a node from the first frame on (Xvfb's, in a scripted screenshot)
  // rings nothing: the picture equals one with the pointer resting on no node. Once it
  // moves, the node under it is ringed.
  LiveOptions o;
  o.paused = true;
  o.hide_panel = true;
  auto on_node = open_app(o);
  auto elsewhere = open_app(o);
  ASSERT_TRUE(on_node && elsewhere);
  const Vec2 p = on_node->to_window(on_node->controller().simulation().x.segment<2>(0));
  Injection still;
  still.x = static_cast<float>(p.x());
  still.y = static_cast<float>(p.y());
  Injection corner;
  corner.x = corner.y = 3.0f;
  Image resting, reference, ringed;
  for (int k = 0; k < 3; ++k) {
    on_node->frame(&still, &resting);
    elsewhere->frame(&corner, &reference);
  }
  EXPECT_EQ(differing_pixels(resting, reference), 0);
  Injection moved = still;
  moved.x += 2.0f;
  on_node->frame(&moved);
  on_node->frame(&moved, &ringed);
  EXPECT_GT(differing_pixels(resting, ringed), 30);
}

TEST(LiveWindow, ANoteMovesNoControl) {
  LiveOptions o;
  o.paused = true;
  auto app = open_app(o);
  ASSERT_TRUE(app);
  app->frame();
  app->frame();
  const std::map<std::string, WidgetRect> before = app->widget_rects();
  type_into(*app, "nu", "0.7");  // clamped: a note
  ASSERT_FALSE(app->controller().note.empty());
  app->frame();
  ASSERT_TRUE(app->widget_rects().count("note"));
  for (const auto& [name, r] : before) {
    ASSERT_TRUE(app->widget_rects().count(name)) << name;
    const WidgetRect& now = app->widget_rects().at(name);
    EXPECT_EQ(now.y0, r.y0) << name;
    EXPECT_EQ(now.x0, r.x0) << name;
  }
  // The note lies over the picture, right of the panel.
  EXPECT_GE(app->widget_rects().at("note").x0, before.at("mu").x1);
}

TEST(LiveWindow, CtrlClickTypesMuAndLambda) {
  LiveOptions o;
  o.paused = true;
  auto app = open_app(o);
  ASSERT_TRUE(app);
  app->frame();
  app->frame();
  for (const auto& [name, value] : {std::pair<std::string, double>{"mu", 2e6}, {"lambda", 0.0}}) {
    const WidgetRect r = app->widget_rects().at(name);
    Injection in;
    in.x = r.x0 + 0.8f * (r.x1 - r.x0);  // far from the handle: a plain click would move it
    in.y = 0.5f * (r.y0 + r.y1);
    in.ctrl = true;
    app->frame(&in);
    in.down[0] = true;
    app->frame(&in);
    in.down[0] = false;
    app->frame(&in);
    in.ctrl = false;
    app->frame(&in);
    Injection select = in;
    select.keys = {GLFW_KEY_A};
    select.ctrl = true;
    app->frame(&select);
    Injection typed = in;
    typed.text = name == "mu" ? "2e6" : "0";
    app->frame(&typed);
    Injection enter = in;
    enter.keys = {GLFW_KEY_ENTER};
    app->frame(&enter);
    app->frame(&in);
    const Lame lame = app->controller().settings().lame;
    EXPECT_EQ(name == "mu" ? lame.mu : lame.lambda, value) << name;
    EXPECT_TRUE(app->controller().note.empty()) << app->controller().note;
  }
}

TEST(LiveWindow, TypedInvalidPoissonRatioIsClampedWithANote) {
  LiveOptions o;
  o.paused = true;
  auto app = open_app(o);
  ASSERT_TRUE(app);
  app->frame();
  Image before, after;
  app->frame(nullptr, &before);
  type_into(*app, "nu", "0.7");
  double E, nu;
  young_poisson_from_lame(app->controller().settings().lame, &E, &nu);
  EXPECT_NEAR(nu, 0.499, 1e-9);
  EXPECT_NEAR(E, 1e5, 1e-3);  // E kept
  EXPECT_NE(app->controller().note.find("nu = 0.7 is outside"), std::string::npos)
      << app->controller().note;
  app->frame(nullptr, &after);
  EXPECT_TRUE(app->widget_rects().count("note"));  // the note is on screen
  EXPECT_GT(differing_pixels(before, after), 500);
  // A valid E is applied as typed, keeping nu.
  type_into(*app, "E", "2e5");
  young_poisson_from_lame(app->controller().settings().lame, &E, &nu);
  EXPECT_NEAR(E, 2e5, 1e-3);
  EXPECT_NEAR(nu, 0.499, 1e-9);
}

}  // namespace
}  // namespace invfree::live
