// Issue 32's window items under Xvfb. Input arrives as GLFW delivers it: the test calls the
// window's own GLFW callbacks (what glfwPollEvents calls for each X event) between two
// frames of a fine mesh, so every event of a "quick" press falls between the same two slow
// frames - the case that lost them. Also: Esc never quits (Ctrl+Q does), presentation
// mode, the method picker, a failure marked in the picture, a new scene framed whole, the
// run's colour range restarted by R, the playback rate, the energy plot's total and the
// bodies' own materials.
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "app/live/live_app.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"

namespace invfree::live {
namespace {

std::unique_ptr<LiveApp> open_app(LiveOptions o, const std::vector<std::string>& sets = {}) {
  if (o.scenes.empty()) {
    for (const auto& e : builtin_scenes()) {
      if (e.name == std::string_view("compress")) o.selected = static_cast<int>(o.scenes.size());
      SceneDef s = *load_builtin_scene(e.name).scene;
      if (e.name == std::string_view("compress")) {
        EXPECT_EQ(apply_overrides(s, sets), "");
      }
      o.scenes.push_back({std::string(e.name), s});
    }
  }
  o.vsync = false;
  std::string error;
  auto app = LiveApp::create(o, &error);
  EXPECT_TRUE(app) << error;
  return app;
}

int scene_index(LiveApp& app, const std::string& name) {
  const auto& scenes = app.controller().scenes();
  for (size_t i = 0; i < scenes.size(); ++i)
    if (scenes[i].label == name) return static_cast<int>(i);
  return -1;
}

// The callbacks GLFW calls from glfwPollEvents for this window (the app's own, whatever
// they do with the events).
struct Glfw {
  GLFWwindow* w = glfwGetCurrentContext();  // the app's window after its frame()
  GLFWkeyfun key_cb = nullptr;
  GLFWcharfun char_cb = nullptr;
  GLFWcursorposfun pos_cb = nullptr;
  GLFWmousebuttonfun button_cb = nullptr;
  Glfw() {
    key_cb = glfwSetKeyCallback(w, nullptr);
    glfwSetKeyCallback(w, key_cb);
    char_cb = glfwSetCharCallback(w, nullptr);
    glfwSetCharCallback(w, char_cb);
    pos_cb = glfwSetCursorPosCallback(w, nullptr);
    glfwSetCursorPosCallback(w, pos_cb);
    button_cb = glfwSetMouseButtonCallback(w, nullptr);
    glfwSetMouseButtonCallback(w, button_cb);
  }
  // One tap: press, the character it types (0: none), release.
  void tap(int key, unsigned c = 0, int mods = 0) const {
    key_cb(w, key, 0, GLFW_PRESS, mods);
    if (c) char_cb(w, c);
    key_cb(w, key, 0, GLFW_RELEASE, mods);
  }
  void move(double x, double y) const { pos_cb(w, x, y); }
  void button(int b, bool down) const { button_cb(w, b, down ? GLFW_PRESS : GLFW_RELEASE, 0); }
};

// compress at n_seg 64 playing: a few frames a second under Xvfb on the project's machine.
std::unique_ptr<LiveApp> open_slow() {
  auto app = open_app({}, {"mesh.n_seg=64"});
  if (app) {
    app->frame();
    app->frame();
  }
  return app;
}

TEST(LiveInput, QuickTapsBetweenTwoSlowFramesAllAct) {
  auto app = open_slow();
  ASSERT_TRUE(app);
  ASSERT_TRUE(app->controller().playing());
  const Glfw g;
  const float s0 = app->view().ui_scale;
  ASSERT_LE(s0 + 1.5f, kMaxUiScale);
  for (int k = 0; k < 4; ++k) g.tap(GLFW_KEY_EQUAL, '=');  // four quick taps of the = key
  app->frame();
  EXPECT_FLOAT_EQ(app->view().ui_scale, s0 + 1.0f);
  g.tap(GLFW_KEY_KP_ADD, '+');         // the numpad's +
  g.tap(GLFW_KEY_RIGHT_BRACKET, '+');  // a German keyboard's + key (a US ] in GLFW's codes)
  app->frame();
  EXPECT_FLOAT_EQ(app->view().ui_scale, s0 + 1.5f);
  for (int k = 0; k < 6; ++k) g.tap(GLFW_KEY_MINUS, '-');
  app->frame();
  EXPECT_FLOAT_EQ(app->view().ui_scale, s0);
  // R: back to step 0 (the frame that read it then takes its one step).
  for (int k = 0; k < 3; ++k) app->frame();
  ASSERT_GT(app->controller().simulation().step_count, 3);
  g.tap(GLFW_KEY_R, 'r');
  app->frame();
  EXPECT_LE(app->controller().simulation().step_count, 1);
  // Space: pauses; two quick Spaces: play on.
  g.tap(GLFW_KEY_SPACE, ' ');
  app->frame();
  EXPECT_FALSE(app->controller().playing());
  g.tap(GLFW_KEY_SPACE, ' ');
  g.tap(GLFW_KEY_SPACE, ' ');
  app->frame();
  EXPECT_FALSE(app->controller().playing());
  g.tap(GLFW_KEY_SPACE, ' ');
  app->frame();
  EXPECT_TRUE(app->controller().playing());
}

TEST(LiveInput, AFastGrabNearANodeGrabsIt) {
  auto app = open_slow();
  ASSERT_TRUE(app);
  const Glfw g;
  // The body's top right corner: no other node is nearer to a point 2 px up and right of it.
  const Simulation& sim = app->controller().simulation();
  int corner = 0;
  for (int i = 0; i < sim.mesh.node_count(); ++i)
    if (sim.x[2 * i] + sim.x[2 * i + 1] > sim.x[2 * corner] + sim.x[2 * corner + 1]) corner = i;
  const Vec2 p = app->to_window(sim.x.segment<2>(2 * corner));
  // All between two frames: onto the node, press, and off quickly with the button held.
  g.move(p.x() + 1.5, p.y() - 1.5);
  g.button(GLFW_MOUSE_BUTTON_LEFT, true);
  g.move(p.x() + 60.0, p.y() - 40.0);
  app->frame();
  EXPECT_TRUE(app->controller().pulling());
  EXPECT_EQ(app->controller().pull_node(), corner);
  g.button(GLFW_MOUSE_BUTTON_LEFT, false);
  app->frame();
  EXPECT_FALSE(app->controller().pulling());
}

void press(LiveApp& app, int key, bool ctrl = false) {
  Injection in;
  in.x = in.y = 3.0f;
  in.keys = {key};
  in.ctrl = ctrl;
  app.frame(&in);
  Injection up;
  up.x = up.y = 3.0f;
  app.frame(&up);
}

void click(LiveApp& app, const WidgetRect& r) {
  Injection in;
  in.x = 0.5f * (r.x0 + r.x1);
  in.y = 0.5f * (r.y0 + r.y1);
  app.frame(&in);
  in.down[0] = true;
  app.frame(&in);
  in.down[0] = false;
  app.frame(&in);
  app.frame(&in);
}

int open_popups() {
  return ImGui::GetCurrentContext()->OpenPopupStack.Size;
}

TEST(LiveInput, EscClosesThePickerAndNeverQuits) {
  LiveOptions o;
  o.paused = true;
  auto app = open_app(o);
  ASSERT_TRUE(app);
  app->frame();
  SceneDef edited = app->controller().settings();
  edited.lame.mu *= 3.0;
  ASSERT_TRUE(app->controller().apply(edited));
  ASSERT_TRUE(app->widget_rects().count("scene"));
  click(*app, app->widget_rects().at("scene"));
  ASSERT_EQ(open_popups(), 1);  // the scene picker's list is open
  press(*app, GLFW_KEY_ESCAPE);
  EXPECT_EQ(open_popups(), 0);
  EXPECT_FALSE(app->should_close());
  EXPECT_EQ(app->controller().settings().lame.mu, edited.lame.mu);
  press(*app, GLFW_KEY_F1);  // the help overlay: Esc closes it
  Image help, closed;
  app->frame(nullptr, &help);
  press(*app, GLFW_KEY_ESCAPE);
  app->frame(nullptr, &closed);
  EXPECT_NE(help.rgba, closed.rgba);
  press(*app, GLFW_KEY_ESCAPE);
  press(*app, GLFW_KEY_ESCAPE);
  EXPECT_FALSE(app->should_close());
  press(*app, GLFW_KEY_Q, true);
  EXPECT_TRUE(app->should_close());
}

TEST(LiveInput, PresentationModeIsFullScreenWithLargeReadouts) {
  LiveOptions o;
  o.paused = true;
  auto app = open_app(o);
  ASSERT_TRUE(app);
  app->frame();
  GLFWwindow* w = glfwGetCurrentContext();
  ASSERT_TRUE(app->widget_rects().count("play"));
  press(*app, GLFW_KEY_P);
  for (int k = 0; k < 3; ++k) app->frame();
  EXPECT_TRUE(app->presenting());
  int ww = 0, wh = 0;
  glfwGetWindowSize(w, &ww, &wh);
  const GLFWvidmode* mode = glfwGetVideoMode(glfwGetPrimaryMonitor());
  ASSERT_NE(mode, nullptr);
  EXPECT_EQ(ww, mode->width);  // Xvfb's screen: 1920x1080 (tests/live/CMakeLists.txt)
  EXPECT_EQ(wh, mode->height);
  EXPECT_FALSE(app->widget_rects().count("play"));  // no panel
  ASSERT_TRUE(app->widget_rects().count("presentation"));
  const WidgetRect r = app->widget_rects().at("presentation");
  // Three lines of at least a twelfth of the height each, and the solver's line.
  EXPECT_GE(r.y1 - r.y0, 3.0f * mode->height / 12.0f);
  press(*app, GLFW_KEY_ESCAPE);  // Esc leaves it
  for (int k = 0; k < 3; ++k) app->frame();
  EXPECT_FALSE(app->presenting());
  glfwGetWindowSize(w, &ww, &wh);
  EXPECT_EQ(ww, 1280);
  EXPECT_EQ(wh, 720);
  EXPECT_TRUE(app->widget_rects().count("play"));
  EXPECT_FALSE(app->should_close());
}

TEST(LiveInput, TheMethodPickerRestartsWithTheMethodKeepingTheSettings) {
  LiveOptions o;
  o.paused = true;
  auto app = open_app(o);
  ASSERT_TRUE(app);
  app->frame();
  SceneDef edited = app->controller().settings();
  edited.lame.mu *= 2.0;
  ASSERT_TRUE(app->controller().apply(edited));
  for (int k = 0; k < 3; ++k) app->controller().step_once();
  ASSERT_TRUE(app->widget_rects().count("method"));
  click(*app, app->widget_rects().at("method"));
  ASSERT_TRUE(app->widget_rects().count("method:symplectic-euler"));
  click(*app, app->widget_rects().at("method:symplectic-euler"));
  const SceneDef& s = app->controller().settings();
  EXPECT_EQ(s.integrator, Integrator::SymplecticEuler);
  EXPECT_EQ(s.lame.mu, edited.lame.mu);
  EXPECT_DOUBLE_EQ(s.h, edited.h / 20.0);
  EXPECT_EQ(app->controller().simulation().step_count, 0);
  click(*app, app->widget_rects().at("method"));
  click(*app, app->widget_rects().at("method:no-inversion-filter"));
  EXPECT_EQ(app->controller().settings().integrator, Integrator::ImplicitEuler);
  EXPECT_FALSE(app->controller().settings().inversion_filter);
  EXPECT_DOUBLE_EQ(app->controller().settings().h, edited.h);
}

long pixels_of(const Image& img, int r, int g, int b) {
  long n = 0;
  for (size_t i = 0; i + 3 < img.rgba.size(); i += 4)
    n += img.rgba[i] == r && img.rgba[i + 1] == g && img.rgba[i + 2] == b;
  return n;
}

TEST(LiveInput, AFailedStepIsMarkedInThePicture) {
  auto app = open_app({});
  ASSERT_TRUE(app);
  for (int k = 0; k < 20; ++k) app->frame();
  Image normal, failed;
  app->controller().set_playing(false);
  Injection still;
  app->frame(&still, &normal);
  SceneDef next = app->controller().settings();
  next.max_newton = 1;  // one iteration cannot meet this tolerance: the step fails
  next.tol = 1e-5;
  ASSERT_TRUE(app->controller().apply(next));
  app->controller().set_playing(true);
  app->frame();
  ASSERT_FALSE(app->controller().banner.empty());
  app->frame(&still, &failed);  // paused: an injected frame is drawn (idle ones wait)
  // The red frame around the picture: thousands of its pixels; none in a normal picture.
  EXPECT_EQ(pixels_of(normal, 220, 30, 40), 0);
  EXPECT_GT(pixels_of(failed, 220, 30, 40), 10000);
}

TEST(LiveInput, ANewSceneIsFramedWholeAndPaused) {
  auto app = open_app({});
  ASSERT_TRUE(app);
  app->frame();
  const int course1 = scene_index(*app, "course-1-mass-spring");
  ASSERT_GE(course1, 0);
  app->controller().select_scene(course1);
  app->frame();
  app->frame();
  EXPECT_FALSE(app->controller().playing());
  const Simulation& sim = app->controller().simulation();
  ASSERT_TRUE(app->widget_rects().count("play"));
  const float panel_right = 390.0f * app->view().ui_scale;
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    const Vec2 p = app->to_window(sim.x.segment<2>(2 * i));
    EXPECT_GE(p.x(), panel_right) << "node " << i;
    EXPECT_LE(p.x(), 1280.0) << "node " << i;
    EXPECT_GE(p.y(), 0.0) << "node " << i;
    EXPECT_LE(p.y(), 720.0) << "node " << i;
  }
}

TEST(LiveInput, ResetStartsTheRunColourRangeAgain) {
  LiveOptions o;
  o.color_range = render::ColorRangeMode::Run;
  auto app = open_app(o);
  ASSERT_TRUE(app);
  for (int k = 0; k < 150; ++k) app->frame();  // 1.5 s: the ceiling squeezes the square
  const double squeezed = app->controller().stats().min_det_f;
  ASSERT_LT(squeezed, 0.95);
  // The run's range holds the bulk of det F (its 10th percentile, as render's; not
  // necessarily its extremes, which would paint the bulk pale).
  const double bulk_lo = render::bulk_det_f_range(app->controller().det_f()).first;
  EXPECT_LE(app->color_range_run().first, bulk_lo);
  app->controller().set_playing(false);
  press(*app, GLFW_KEY_R);
  EXPECT_EQ(app->controller().simulation().step_count, 0);
  EXPECT_GT(app->color_range_run().first, 0.99)  // the initial state's, not the squeeze's
      << "squeezed " << squeezed << ", now " << app->controller().stats().min_det_f;
  const int stack = scene_index(*app, "stack");
  ASSERT_GE(stack, 0);
  app->controller().set_playing(true);
  for (int k = 0; k < 150; ++k) app->frame();
  ASSERT_LT(app->color_range_run().first, 0.99);
  app->controller().select_scene(stack);  // (paused: an injected frame is drawn)
  Injection still;
  app->frame(&still);
  EXPECT_GT(app->color_range_run().first, 0.99);
}

TEST(LiveInput, ThePlaybackRateAgainstRealTimeIsMeasured) {
  auto app = open_app({});
  ASSERT_TRUE(app);
  app->frame();
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const double sim0 = app->controller().simulation().time;
  for (int k = 0; k < 2000 && !app->real_time_rate(); ++k) app->frame();
  ASSERT_TRUE(app->real_time_rate());
  for (int k = 0; k < 30; ++k) app->frame();
  const double wall = std::chrono::duration<double>(clock::now() - t0).count();
  const double mean = (app->controller().simulation().time - sim0) / wall;
  // The last two seconds' rate against the whole run's: the same machine, the same scene.
  EXPECT_GT(*app->real_time_rate(), 0.3 * mean);
  EXPECT_LT(*app->real_time_rate(), 3.0 * mean);
}

TEST(LiveInput, TheEnergyPlotDrawsTheTotal) {
  auto app = open_app({});
  ASSERT_TRUE(app);
  for (int k = 0; k < 30; ++k) app->frame();
  Image img;
  app->frame(nullptr, &img);
  ASSERT_TRUE(app->widget_rects().count("energy_plot"));
  const WidgetRect r = app->widget_rects().at("energy_plot");
  // Whitish pixels: none of the four energies' colours (orange, blue, green, red) nor the
  // plot's blue-grey ground has all three channels above 170.
  long white = 0;
  // (the panel scrolls: the plot may reach below the window's edge)
  for (int y = std::max(0, static_cast<int>(r.y0));
       y < std::min(img.height, static_cast<int>(r.y1)); ++y)
    for (int x = std::max(0, static_cast<int>(r.x0));
         x < std::min(img.width, static_cast<int>(r.x1)); ++x) {
      const size_t i = 4 * (static_cast<size_t>(y) * img.width + x);
      white += std::min({img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]}) > 170;
    }
  EXPECT_GT(white, 20);  // the total's white line
}

TEST(LiveInput, BodiesWithTheirOwnMaterialAreLabelled) {
  const std::string dir = ::testing::TempDir() + "/live_input_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/two-materials.toml";
  {
    std::ofstream f(file);
    f << "[mesh]\nside = 0.4\nn_seg = 3\n[[body]]\noffset = [0.0, 0.0]\nE = 1e5\n"
         "[[body]]\noffset = [0.0, -0.6]\nE = 1e6\n[ground]\ny = -1.0\n";
  }
  const SceneLoad loaded = load_scene(file);
  ASSERT_TRUE(loaded.scene) << loaded.error;
  LiveOptions o;
  o.paused = true;
  o.scenes = {{file, *loaded.scene}, {"compress", *load_builtin_scene("compress").scene}};
  auto app = open_app(o);
  ASSERT_TRUE(app);
  app->frame();
  EXPECT_TRUE(app->widget_rects().count("body_materials"));
  app->controller().select_scene(1);
  app->frame();
  EXPECT_FALSE(app->widget_rects().count("body_materials"));
}

TEST(LiveInput, EveryControlOfThePanelFitsTheWindowAt1280x720) {
  // The panel is as high as the window and scrolls where its rows are longer; at 1280x720,
  // UI scale 1 (the projector's window), every control and plot of it lies inside the
  // window in every built-in scene (their rows differ: a chapter's note, several bodies'
  // friction, a course scene's mass-spring rows), so none needs the scroll bar to reach.
  auto app = open_app({});
  ASSERT_TRUE(app);
  app->frame();
  ASSERT_EQ(app->view().ui_scale, 1.0f);
  const auto& scenes = app->controller().scenes();
  for (size_t i = 0; i < scenes.size(); ++i) {
    app->controller().select_scene(static_cast<int>(i));
    app->frame();
    app->frame();
    const auto& rects = app->widget_rects();
    ASSERT_TRUE(rects.count("panel")) << scenes[i].label;
    const WidgetRect panel = rects.at("panel");
    EXPECT_EQ(panel.y0, 0.0f);
    EXPECT_EQ(panel.y1, 720.0f);
    ASSERT_TRUE(rects.count("energy_plot")) << scenes[i].label;  // the panel's last row
    for (const auto& [name, r] : rects) {
      // (not the panel's rows: the panel itself, the windows and notes over the picture)
      if (name == "panel" || name == "picture" || name == "note" || name == "inspector" ||
          name == "landscape_window" || name == "presentation" || name.rfind("method:", 0) == 0)
        continue;
      EXPECT_LE(r.y1, panel.y1) << scenes[i].label << ": " << name << " ends at y " << r.y1;
    }
  }
}

}  // namespace
}  // namespace invfree::live
