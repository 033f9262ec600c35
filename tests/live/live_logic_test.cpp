// The live mode's window-independent logic: parameter limits and the E/nu <-> mu/lambda
// edits, the log slider mapping, the stats histories, the key table, output naming, and
// the simulation controller (changes in the middle of a compression keep the state
// valid; a failed step pauses and keeps the last good state).
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string_view>

#include "app/live/course.h"
#include "app/live/key_bindings.h"
#include "app/live/live_controller.h"
#include "app/live/log_slider.h"
#include "app/live/method_choice.h"
#include "app/live/real_time_rate.h"
#include "app/live/scene_label.h"
#include "app/live/output_naming.h"
#include "app/live/param_limits.h"
#include "app/live/plot_range.h"
#include "app/live/view_transform.h"
#include "material/triangle_elasticity.h"
#include "scene_io/builtin_scenes.h"

namespace invfree::live {
namespace {

bool in_range(double v, Range r) {
  return v >= r.lo && v <= r.hi;
}

TEST(LiveParams, ClampKeepsInRangeValuesAndNotesTheOthers) {
  Clamped c = clamp_to_range(0.01, 0.02, kTimeStepRange, "h", "s");
  EXPECT_EQ(c.value, 0.01);
  EXPECT_TRUE(c.note.empty());
  c = clamp_to_range(1.0, 0.02, kTimeStepRange, "h", "s");
  EXPECT_EQ(c.value, kTimeStepRange.hi);
  EXPECT_NE(c.note.find("h = 1 is outside"), std::string::npos) << c.note;
  c = clamp_to_range(-3.0, 0.02, kTimeStepRange, "h", "s");
  EXPECT_EQ(c.value, kTimeStepRange.lo);
  EXPECT_FALSE(c.note.empty());
  c = clamp_to_range(std::nan(""), 0.02, kTimeStepRange, "h", "s");
  EXPECT_EQ(c.value, 0.02);
  EXPECT_NE(c.note.find("not applied"), std::string::npos);
  c = clamp_to_range(INFINITY, 0.02, kTimeStepRange, "h", "s");
  EXPECT_EQ(c.value, 0.02);
}

TEST(LiveParams, EveryMaterialEditStaysValid) {
  const double requests[] = {-1e9, -1.0,  0.0, 1e-3, 0.3, 0.499, 0.5, 0.7,      1.0,      50.0,
                             1e3,  3.5e4, 1e6, 1e8,  1e9, 1e12,  NAN, INFINITY, -INFINITY};
  const Lame starts[] = {lame_from_young_poisson(1e5, 0.4),
                         {kMuRange.lo, 0.0},
                         {kMuRange.hi, kLambdaRange.hi},
                         {kMuRange.lo, kLambdaRange.hi},
                         {kMuRange.hi, 0.0}};
  for (const Lame& start : starts) {
    for (double r : requests) {
      for (const MaterialEdit& e : {edit_mu(start, r), edit_lambda(start, r), edit_young(start, r),
                                    edit_poisson(start, r)}) {
        EXPECT_TRUE(in_range(e.lame.mu, kMuRange)) << e.lame.mu << " from request " << r;
        EXPECT_TRUE(in_range(e.lame.lambda, kLambdaRange))
            << e.lame.lambda << " from request " << r;
        double E, nu;
        young_poisson_from_lame(e.lame, &E, &nu);
        EXPECT_TRUE(std::isfinite(E) && E > 0.0);
        EXPECT_TRUE(nu >= 0.0 && nu < 0.5) << nu;
        if (!std::isfinite(r)) {
          EXPECT_EQ(e.lame, start);
          EXPECT_FALSE(e.note.empty());
        }
      }
    }
  }
}

TEST(LiveParams, YoungAndPoissonEditsKeepTheOtherOne) {
  const Lame start = lame_from_young_poisson(1e5, 0.4);
  MaterialEdit e = edit_young(start, 2e5);
  EXPECT_TRUE(e.note.empty()) << e.note;
  double E, nu;
  young_poisson_from_lame(e.lame, &E, &nu);
  EXPECT_NEAR(E, 2e5, 1e-6);
  EXPECT_NEAR(nu, 0.4, 1e-12);
  EXPECT_NEAR(e.lame.mu, 2e5 / 2.8, 1e-6);

  e = edit_poisson(start, 0.25);
  EXPECT_TRUE(e.note.empty()) << e.note;
  young_poisson_from_lame(e.lame, &E, &nu);
  EXPECT_NEAR(E, 1e5, 1e-6);
  EXPECT_NEAR(nu, 0.25, 1e-12);

  // nu >= 0.5 is not a material: clamped just below, with a note.
  e = edit_poisson(start, 0.5);
  EXPECT_NE(e.note.find("nu = 0.5 is outside"), std::string::npos) << e.note;
  young_poisson_from_lame(e.lame, &E, &nu);
  EXPECT_NEAR(nu, kPoissonRange.hi, 1e-9);
  EXPECT_NEAR(E, 1e5, 1e-6);

  e = edit_poisson(start, 0.0);
  EXPECT_EQ(e.lame.lambda, 0.0);
  e = edit_mu(start, 1e10);
  EXPECT_EQ(e.lame.mu, kMuRange.hi);
  EXPECT_EQ(e.lame.lambda, start.lambda);
  EXPECT_NE(e.note.find("clamped"), std::string::npos);
  e = edit_lambda(start, -5.0);
  EXPECT_EQ(e.lame.lambda, 0.0);
  EXPECT_EQ(e.lame.mu, start.mu);
}

TEST(LiveParams, PoissonRangeShrinksWhenLambdaWouldLeaveItsRange) {
  const Lame stiff = lame_from_young_poisson(2e7, 0.3);
  const MaterialEdit e = edit_poisson(stiff, 0.49);
  EXPECT_FALSE(e.note.empty());
  EXPECT_LE(e.lame.lambda, kLambdaRange.hi);
  EXPECT_GT(e.lame.lambda, 0.9 * kLambdaRange.hi);  // clamped to the edge, not far below it
}

TEST(LiveParams, CeilingStopRange) {
  const Range r = ceiling_stop_range(-1.0, true, 0.6, 1.0);
  EXPECT_DOUBLE_EQ(r.lo, -0.9);
  EXPECT_DOUBLE_EQ(r.hi, 0.6);
}

// The sliders' ranges are the scene field table's "slider range" column: each lies inside
// its key's valid range, and they are the ranges the panel has always had.
TEST(LiveParams, SliderRangesAreTheFieldTablesAndLieInsideTheValidRanges) {
  int sliders = 0;
  for (const SceneField& f : scene_fields()) {
    if (!f.slider.any()) continue;
    ++sliders;
    EXPECT_TRUE(f.bounds.contains(f.slider.lo)) << f.name();
    EXPECT_TRUE(f.bounds.contains(f.slider.hi)) << f.name();
    const Range r = slider_range(f.name());
    EXPECT_EQ(r.lo, f.slider.lo);
    EXPECT_EQ(r.hi, f.slider.hi);
  }
  EXPECT_EQ(sliders, 8);
  auto same = [](Range a, double lo, double hi) { return a.lo == lo && a.hi == hi; };
  EXPECT_TRUE(same(kMuRange, 1e2, 1e7));
  EXPECT_TRUE(same(kLambdaRange, 0.0, 1e8));
  EXPECT_TRUE(same(kPoissonRange, 0.0, 0.499));
  EXPECT_TRUE(same(kTimeStepRange, 1e-4, 0.05));
  EXPECT_TRUE(same(kTolRange, 1e-5, 1.0));
  EXPECT_TRUE(same(kFrictionRange, 0.0, 2.0));
  EXPECT_TRUE(same(kCeilingSpeedRange, 0.0, 5.0));
  EXPECT_FALSE(std::signbit(kCeilingSpeedRange.lo));  // "[0, 5]" in its note, not "[-0, 5]"
  EXPECT_TRUE(same(kSpringStiffnessRange, 1e1, 1e8));
  EXPECT_EQ(kMinSegments, 1);
  EXPECT_TRUE(same(slider_range("mesh.side"), 0.0, 0.0));  // no slider
}

TEST(LiveSlider, LogMappingRoundTripsAndIsLogarithmic) {
  const LogSlider s{1e2, 1e8};
  EXPECT_DOUBLE_EQ(s.value(0.0), 1e2);
  EXPECT_NEAR(s.value(1.0), 1e8, 1e-6);
  EXPECT_NEAR(s.value(0.5), 1e5, 1e-8);
  for (double t = 0.0; t <= 1.0; t += 0.05) EXPECT_NEAR(s.position(s.value(t)), t, 1e-12);
  EXPECT_EQ(s.position(1.0), 0.0);
  EXPECT_EQ(s.position(1e12), 1.0);
  EXPECT_EQ(s.position(std::nan("")), 0.0);
  const LogSlider z{1e2, 1e9, true};
  EXPECT_EQ(z.value(0.0), 0.0);
  EXPECT_EQ(z.position(0.0), 0.0);
  EXPECT_NEAR(z.value(1e-9), 1e2, 1e-3);
}

TEST(LiveSlider, TheRightEndIsTheRangesEndWithoutANote) {
  // Clicking the mu slider's right end gave 1.0000000000000002e7 and the note "mu = 1e+07 is
  // outside [100, 1e+07] Pa; clamped": the end of the range is inside it.
  const LogSlider mu{kMuRange.lo, kMuRange.hi};
  EXPECT_EQ(mu.value(1.0), kMuRange.hi);
  EXPECT_EQ(mu.value(0.0), kMuRange.lo);
  const MaterialEdit e = edit_mu({1e4, 1e4}, mu.value(1.0));
  EXPECT_EQ(e.lame.mu, kMuRange.hi);
  EXPECT_TRUE(e.note.empty()) << e.note;
  const LogSlider lambda{kLambdaLogMin, kLambdaRange.hi, true};
  EXPECT_TRUE(edit_lambda({1e4, 1e4}, lambda.value(1.0)).note.empty());
  for (double t = 0.0; t <= 1.0; t += 1.0 / 64)
    EXPECT_TRUE(edit_mu({1e4, 1e4}, mu.value(t)).note.empty()) << t;
}

TEST(LiveStats, HistoryKeepsTheLastValuesOldestFirst) {
  StatsHistory h(4);
  EXPECT_TRUE(h.empty());
  for (int i = 1; i <= 6; ++i) h.push(float(i));
  EXPECT_EQ(h.size(), 4u);
  EXPECT_EQ(h.values(), (std::vector<float>{3, 4, 5, 6}));
  EXPECT_EQ(h.back(), 6.0f);
  EXPECT_EQ(h.min(), 3.0f);
  EXPECT_EQ(h.max(), 6.0f);
  h.clear();
  EXPECT_TRUE(h.values().empty());
}

TEST(LiveKeys, KeysMapToTheirActionsOnceAndAreInTheHelp) {
  EXPECT_EQ(action_for_key(GLFW_KEY_SPACE, 0), Action::TogglePlay);
  EXPECT_EQ(action_for_key(GLFW_KEY_S, 0), Action::Step);
  EXPECT_EQ(action_for_key(GLFW_KEY_R, 0), Action::Reset);
  EXPECT_EQ(action_for_key(GLFW_KEY_TAB, 0), Action::TogglePanel);
  EXPECT_EQ(action_for_key(GLFW_KEY_F1, 0), Action::ToggleHelp);
  EXPECT_EQ(action_for_key(GLFW_KEY_P, GLFW_MOD_CONTROL), Action::Screenshot);
  // Esc closes what is open and never quits; Ctrl+Q quits (issue 32).
  EXPECT_EQ(action_for_key(GLFW_KEY_ESCAPE, 0), Action::Back);
  EXPECT_EQ(action_for_key(GLFW_KEY_Q, GLFW_MOD_CONTROL), Action::Quit);
  EXPECT_EQ(action_for_key(GLFW_KEY_Q, 0), std::nullopt);
  EXPECT_EQ(action_for_key(GLFW_KEY_P, 0), Action::Presentation);
  // + and - are what is typed, on any layout: the = key's '=', a keypad's or a German
  // keyboard's '+'; the key code of the = key alone does nothing.
  EXPECT_EQ(action_for_char('+'), Action::UiScaleUp);
  EXPECT_EQ(action_for_char('='), Action::UiScaleUp);
  EXPECT_EQ(action_for_char('-'), Action::UiScaleDown);
  EXPECT_EQ(action_for_char('r'), std::nullopt);
  EXPECT_EQ(action_for_key(GLFW_KEY_EQUAL, 0), std::nullopt);
  EXPECT_EQ(action_for_key(GLFW_KEY_SPACE, GLFW_MOD_SHIFT), Action::TogglePlay);
  std::set<std::pair<int, int>> seen;
  const std::string help = help_text();
  for (const auto& b : key_bindings()) {
    const int code = b.key == kTypedKey ? 1000 + b.chars[0] : b.key;
    EXPECT_TRUE(seen.insert({code, b.mods}).second) << b.key_name << " bound twice";
    EXPECT_NE(help.find(b.key_name), std::string::npos) << b.key_name;
    EXPECT_NE(help.find(b.description), std::string::npos);
  }
  for (const auto& m : mouse_bindings()) EXPECT_NE(help.find(m.gesture), std::string::npos);
}

TEST(LiveOutput, ScreenshotsAreNumberedWithoutOverwriting) {
  const std::string dir = ::testing::TempDir() + "/live_shots_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  EXPECT_EQ(next_screenshot_path(dir), dir + "/invfree_0001.png");
  std::ofstream(dir + "/invfree_0001.png") << "x";
  std::ofstream(dir + "/invfree_0002.png") << "x";
  EXPECT_EQ(next_screenshot_path(dir), dir + "/invfree_0003.png");
  EXPECT_EQ(record_frame_path("out", 0), "out/frame_000000.png");
  EXPECT_EQ(record_frame_path("out", 1234), "out/frame_001234.png");
  std::filesystem::remove_all(dir);
}

TEST(LiveView, ScreenAndWorldMapsAreInverseAndZoomKeepsTheAnchor) {
  ViewTransform v;
  v.width = 800;
  v.height = 600;
  v.fit({-1.0, -1.0, 1.0, 0.6}, 200.0, 20.0, 560.0, 560.0);
  // The box fits in the rectangle, touches two of its sides, and is centred in it.
  const Vec2 a = v.to_screen({-1.0, -1.0}), b = v.to_screen({1.0, 0.6});
  EXPECT_GE(a.x(), 200.0 - 1e-9);
  EXPECT_LE(b.x(), 760.0 + 1e-9);
  EXPECT_GE(b.y(), 20.0 - 1e-9);  // y points down on screen
  EXPECT_LE(a.y(), 580.0 + 1e-9);
  EXPECT_NEAR(b.x() - a.x(), 560.0, 1e-9);
  EXPECT_NEAR(0.5 * (a.x() + b.x()), 480.0, 1e-9);
  EXPECT_NEAR(0.5 * (a.y() + b.y()), 300.0, 1e-9);
  const Vec2 p(0.3, -0.2);
  EXPECT_NEAR((v.to_world(v.to_screen(p)) - p).norm(), 0.0, 1e-12);
  const Vec2 s(123.0, 456.0);
  const Vec2 w = v.to_world(s);
  v.zoom_at(s, 1.7);
  EXPECT_NEAR((v.to_screen(w) - s).norm(), 0.0, 1e-9);
  const double ppm = v.pixels_per_metre;
  v.pan(10.0, -5.0);
  EXPECT_NEAR((v.to_screen(w) - (s + Vec2(10.0, -5.0))).norm(), 0.0, 1e-9);
  EXPECT_EQ(v.pixels_per_metre, ppm);
  const WorldBox vis = v.visible();
  EXPECT_NEAR((vis.x1 - vis.x0) * ppm, 800.0, 1e-9);
  EXPECT_NEAR((vis.y1 - vis.y0) * ppm, 600.0, 1e-9);
}

// --- the controller

// Every built-in scene, compress first (index 0; the rest in name order, where the shape
// scene bunny now precedes it).
std::vector<SceneChoice> compress_choices() {
  std::vector<SceneChoice> c = {{"compress", *load_builtin_scene("compress").scene}};
  for (const auto& e : builtin_scenes())
    if (e.name != std::string_view("compress"))
      c.push_back({std::string(e.name), *load_builtin_scene(e.name).scene});
  return c;
}

// The state invariants the live mode promises after any edit: finite, no inversion for a
// model that forbids it, every node strictly between ground and ceiling.
void expect_valid_state(const LiveController& lc, const std::string& context) {
  const Simulation& s = lc.simulation();
  ASSERT_TRUE(s.x.allFinite() && s.v.allFinite()) << context;
  if (!model_allows_inversion(s.scene.model)) {
    for (double d : triangle_det_f(s)) {
      ASSERT_GT(d, 0.0) << context;
    }
  }
  for (int i = 0; i < s.mesh.node_count(); ++i) {
    const double y = s.x[2 * i + 1];
    if (s.scene.has_ground) {
      ASSERT_GT(y, s.scene.ground_y) << context;
    }
    if (s.scene.has_ceiling) {
      ASSERT_LT(y, s.ceiling_y) << context;
    }
  }
}

TEST(LiveController, EditsInTheMiddleOfACompressionKeepTheStateValid) {
  LiveController lc(compress_choices(), 0);
  ASSERT_EQ(lc.settings().name, "compress");
  for (int k = 0; k < 170; ++k) ASSERT_TRUE(lc.step_once()) << lc.banner;
  // The ceiling is pressing on the square now.
  ASSERT_LT(lc.simulation().ceiling_y, 0.0);
  ASSERT_LT(lc.stats().min_det_f, 0.9);

  struct Edit {
    const char* what;
    MaterialEdit (*edit)(const Lame&, double);
    double value;
  };
  // Jumps across the range the demo runs at (far stiffer squares make the penalty ceiling
  // hit Newton's cap: that pauses with a banner, tested below).
  const Edit edits[] = {{"mu soft", edit_mu, 1e2},       {"mu stiff", edit_mu, 3e5},
                        {"lambda 0", edit_lambda, 0.0},  {"lambda stiff", edit_lambda, 3e6},
                        {"nu 0.45", edit_poisson, 0.45}, {"E soft", edit_young, 1e3},
                        {"back", edit_young, 1e5}};
  for (const Edit& e : edits) {
    SceneDef next = lc.settings();
    next.lame = e.edit(next.lame, e.value).lame;
    ASSERT_TRUE(lc.apply(next)) << lc.note;
    EXPECT_EQ(lc.settings().lame, next.lame);
    for (int k = 0; k < 15; ++k) {
      lc.step_once();
      expect_valid_state(lc, e.what);
    }
    EXPECT_TRUE(lc.banner.empty()) << e.what << ": " << lc.banner;
  }
  for (Model m : {Model::StableNeoHookean, Model::Arap, Model::Linear, Model::NeoHookean}) {
    SceneDef next = lc.settings();
    next.model = m;
    const bool applied = lc.apply(next);
    // Back to neo-Hookean is refused only while some triangle is inverted.
    if (!applied) {
      EXPECT_EQ(m, Model::NeoHookean);
      EXPECT_GT(lc.stats().inverted, 0);
      continue;
    }
    for (int k = 0; k < 15; ++k) {
      lc.step_once();
      expect_valid_state(lc, model_name(m));
    }
    EXPECT_TRUE(lc.banner.empty()) << model_name(m) << ": " << lc.banner;
  }
}

TEST(LiveController, SwitchingToNeoHookeanIsRefusedWhileInverted) {
  SceneDef soft = *load_builtin_scene("compress").scene;
  soft.model = Model::Linear;
  soft.lame = {1e2, 0.0};  // far too soft for its weight: linear elasticity inverts
  LiveController lc({{"soft", soft}}, 0);
  for (int k = 0; k < 200 && lc.stats().inverted == 0; ++k) lc.step_once();
  ASSERT_GT(lc.stats().inverted, 0) << "the test needs an inverted state";
  const VecX x_before = lc.simulation().x;
  SceneDef next = lc.settings();
  next.model = Model::NeoHookean;
  EXPECT_FALSE(lc.apply(next));
  EXPECT_NE(lc.note.find("inverted"), std::string::npos) << lc.note;
  EXPECT_EQ(lc.settings().model, Model::Linear);
  EXPECT_EQ(lc.simulation().x, x_before);
  lc.reset();  // from the initial state the switch is fine
  EXPECT_TRUE(lc.apply(next)) << lc.note;
  EXPECT_EQ(lc.settings().model, Model::NeoHookean);
}

TEST(LiveController, AFailedStepPausesAndKeepsTheLastGoodState) {
  LiveController lc(compress_choices(), 0);
  for (int k = 0; k < 20; ++k) ASSERT_TRUE(lc.step_once());
  SceneDef next = lc.settings();
  next.max_newton = 1;  // one iteration cannot meet this tolerance: the iteration cap
  next.tol = 1e-5;
  ASSERT_TRUE(lc.apply(next)) << lc.note;
  lc.set_playing(true);
  const VecX x = lc.simulation().x;
  const long n = lc.simulation().step_count;
  EXPECT_EQ(lc.advance_frame(), 0);
  EXPECT_FALSE(lc.playing());
  EXPECT_NE(lc.banner.find("failed"), std::string::npos) << lc.banner;
  EXPECT_EQ(lc.simulation().x, x);
  EXPECT_EQ(lc.simulation().step_count, n);
  expect_valid_state(lc, "after failure");
  // A setting that works lets it go on.
  next.max_newton = 100;
  next.tol = 1e-2;
  ASSERT_TRUE(lc.apply(next));
  EXPECT_TRUE(lc.step_once());
  EXPECT_TRUE(lc.banner.empty());
}

TEST(LiveController, InvalidSettingsAreRefusedAndMeshChangesRestart) {
  LiveController lc(compress_choices(), 0);
  for (int k = 0; k < 5; ++k) lc.step_once();
  SceneDef bad = lc.settings();
  bad.h = -1.0;
  EXPECT_FALSE(lc.apply(bad));
  EXPECT_NE(lc.note.find("time.h"), std::string::npos) << lc.note;
  EXPECT_EQ(lc.settings().h, 0.01);
  EXPECT_EQ(lc.simulation().step_count, 5);

  SceneDef finer = lc.settings();
  finer.n_seg = 8;
  EXPECT_TRUE(lc.apply(finer));
  EXPECT_EQ(lc.simulation().mesh.node_count(), 81);
  EXPECT_EQ(lc.simulation().step_count, 0);
  EXPECT_TRUE(lc.ms_history().empty());
  EXPECT_NE(lc.note.find("rebuilt"), std::string::npos);

  // Reset keeps the edited settings; selecting a scene loads its own.
  SceneDef h2 = lc.settings();
  h2.h = 0.005;
  ASSERT_TRUE(lc.apply(h2));
  lc.step_once();
  lc.reset();
  EXPECT_EQ(lc.simulation().step_count, 0);
  EXPECT_EQ(lc.settings().h, 0.005);
  EXPECT_EQ(lc.settings().n_seg, 8);
  const auto choices = compress_choices();
  const auto drop = std::find_if(choices.begin(), choices.end(),
                                 [](const SceneChoice& c) { return c.label == "drop"; });
  ASSERT_NE(drop, choices.end());
  lc.select_scene(static_cast<int>(drop - choices.begin()));
  EXPECT_EQ(lc.settings().name, "drop");
  EXPECT_EQ(lc.settings().n_seg, load_builtin_scene("drop").scene->n_seg);
  EXPECT_FALSE(lc.settings().has_ceiling);
}

TEST(LiveController, StatsFollowTheState) {
  LiveController lc(compress_choices(), 0);
  EXPECT_FALSE(lc.has_stepped());
  EXPECT_EQ(lc.det_f().size(), static_cast<size_t>(lc.simulation().mesh.triangle_count()));
  EXPECT_NEAR(lc.stats().min_det_f, 1.0, 1e-12);
  lc.set_playing(true);
  lc.steps_per_frame = 3;
  EXPECT_EQ(lc.advance_frame(), 3);
  EXPECT_EQ(lc.ms_history().size(), 3u);
  EXPECT_EQ(lc.min_det_history().back(), static_cast<float>(lc.stats().min_det_f));
  const auto det = triangle_det_f(lc.simulation());
  EXPECT_EQ(lc.det_f(), det);
  lc.set_playing(false);
  EXPECT_EQ(lc.advance_frame(), 0);
  EXPECT_EQ(lc.simulation().step_count, 3);
  const Vec2 p = lc.simulation().x.segment<2>(2 * 7);
  EXPECT_EQ(lc.nearest_node(p + Vec2(0.01, 0.0), 0.05), 7);
  EXPECT_EQ(lc.nearest_node(Vec2(5.0, 5.0), 0.05), -1);
}

// The picker lists the course first, in chapter order from chapter 0 (its three demos) on,
// every chapter 0 to 8 there (each a built-in scene), then the other built-in scenes; each
// chapter has an idea, the lecture's own `compress` too (issue 32: it had none).
TEST(Course, ThePickerListsTheChaptersInOrderThenTheRest) {
  std::vector<std::string> names;
  for (const auto& e : builtin_scenes()) names.emplace_back(e.name);
  put_course_first(names);
  ASSERT_GE(names.size(), std::size(kCourse));
  std::set<int> chapters;
  for (size_t k = 0; k < std::size(kCourse); ++k) {
    EXPECT_EQ(names[k], kCourse[k].scene) << "position " << k;
    if (k > 0) {
      EXPECT_GE(kCourse[k].chapter, kCourse[k - 1].chapter) << kCourse[k].scene;
    }
    chapters.insert(kCourse[k].chapter);
    EXPECT_NE(kCourse[k].idea, nullptr) << kCourse[k].scene;
  }
  for (int c = 0; c <= 8; ++c) EXPECT_EQ(chapters.count(c), 1u) << "chapter " << c;
  EXPECT_EQ(names[0], "course-0-free-fall");
  EXPECT_EQ(names[1], "course-0-spring");
  EXPECT_EQ(names[2], "course-0-mass-spring");
  for (size_t k = std::size(kCourse); k < names.size(); ++k)
    EXPECT_EQ(course_chapter(names[k]), nullptr) << names[k];
}

// A plot's y range holds its data and spans at least the minimum the panel gives it, so a
// change of 0.001 in min det F takes a tenth of the plot's height (labelled), not all of it.
TEST(PlotRange, HoldsTheDataAndSpansAtLeastTheMinimum) {
  const std::vector<float> flat = {0.998f, 0.9985f, 0.999f};
  const PlotRange r = plot_y_range(flat, 0.01f);
  EXPECT_NEAR(r.hi - r.lo, 0.01f, 1e-6f);
  EXPECT_LE(r.lo, 0.998f);
  EXPECT_GE(r.hi, 0.999f);
  EXPECT_LT((0.999f - 0.998f) / (r.hi - r.lo), 0.11f);
  const std::vector<float> wide = {-3.0f, 5.0f, 1.0f};
  const PlotRange w = plot_y_range(wide, 0.01f);
  EXPECT_EQ(w.lo, -3.0f);
  EXPECT_EQ(w.hi, 5.0f);
  const PlotRange none = plot_y_range({}, 1.0f);
  EXPECT_EQ(none.hi - none.lo, 1.0f);
}

}  // namespace
}  // namespace invfree::live

namespace invfree::live {
namespace {

std::vector<SceneChoice> two_scenes() {
  std::vector<SceneChoice> c;
  for (const char* name : {"compress", "course-1-mass-spring"})
    c.push_back({name, *load_builtin_scene(name).scene});
  return c;
}

// Issue 32: a new scene started playing at once, so the class missed its start.
TEST(LiveController, ANewSceneStartsPausedAtTimeZero) {
  LiveController lc(two_scenes(), 0);
  lc.set_playing(true);
  for (int k = 0; k < 5; ++k) ASSERT_TRUE(lc.step_once());
  const long restarts = lc.restarts();
  lc.select_scene(1);
  EXPECT_FALSE(lc.playing());
  EXPECT_EQ(lc.simulation().step_count, 0);
  EXPECT_EQ(lc.simulation().time, 0.0);
  EXPECT_GT(lc.restarts(), restarts);
  EXPECT_EQ(lc.advance_frame(), 0);  // nothing moves until play
  EXPECT_EQ(lc.simulation().step_count, 0);
  const long after_select = lc.restarts();
  lc.reset();
  EXPECT_GT(lc.restarts(), after_select);  // R restarts the run's gathering too
}

// The method picker: each method is the study's overrides on the edited scene; switching
// restarts at t = 0 and keeps the rest (material, mesh, time step); symplectic Euler's h is
// the implicit h over its substeps, and switching back gives the h that was set.
TEST(LiveMethods, SwitchingKeepsTheOtherSettingsAndRestarts) {
  LiveController lc(two_scenes(), 0);
  SceneDef edited = lc.settings();
  edited.lame.mu *= 2.0;
  edited.h = 0.005;
  edited.n_seg = 6;
  ASSERT_TRUE(lc.apply(edited)) << lc.note;
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(lc.step_once());
  ASSERT_NE(current_method(lc.settings()), nullptr);
  EXPECT_STREQ(current_method(lc.settings())->name, "lecture");
  EXPECT_NE(solver_caption(lc.settings()).find("implicit Euler"), std::string::npos);
  for (const LiveMethod& m : live_methods()) {
    const Method* method = find_method(m.name);
    ASSERT_NE(method, nullptr) << m.name;
    SceneDef next;
    ASSERT_EQ(switch_method(lc.settings(), *method, &next), "") << m.name;
    ASSERT_TRUE(lc.restart_with(next)) << lc.note;
    EXPECT_EQ(lc.simulation().step_count, 0) << m.name;
    ASSERT_NE(current_method(lc.settings()), nullptr) << m.name;
    EXPECT_STREQ(current_method(lc.settings())->name, m.name);
    EXPECT_EQ(lc.settings().lame.mu, edited.lame.mu) << m.name;
    EXPECT_EQ(lc.settings().n_seg, 6) << m.name;
    EXPECT_DOUBLE_EQ(lc.settings().h, 0.005 / method->substeps) << m.name;
    EXPECT_TRUE(lc.step_once()) << m.name << ": " << lc.banner;
  }
  SceneDef back;
  ASSERT_EQ(switch_method(lc.settings(), *find_method("symplectic-euler"), &back), "");
  ASSERT_TRUE(lc.restart_with(back));
  EXPECT_NE(solver_caption(lc.settings()).find("symplectic Euler"), std::string::npos);
  ASSERT_EQ(switch_method(lc.settings(), *find_method("no-projection"), &back), "");
  ASSERT_TRUE(lc.restart_with(back));
  EXPECT_DOUBLE_EQ(lc.settings().h, 0.005);
  EXPECT_NE(solver_caption(lc.settings()).find("no projection"), std::string::npos);
  SceneDef arap = lc.settings();
  arap.model = Model::Arap;
  EXPECT_EQ(current_method(arap), nullptr);  // none of the picker's
}

TEST(LiveScenes, AFileShowsAsItsFileName) {
  EXPECT_EQ(scene_display_name("compress"), "compress");
  EXPECT_EQ(scene_display_name("/home/teacher/lectures/week 3/my-long-scene.toml"),
            "my-long-scene.toml");
  EXPECT_EQ(scene_display_name("scenes/a.toml"), "a.toml");
}

TEST(LiveRealTime, RateIsSimulatedOverWallSeconds) {
  RealTimeRate r;
  EXPECT_FALSE(r.rate());
  for (int k = 0; k <= 100; ++k) r.count(0.002 * k, true, 0.01 * k);  // 0.2 s per second
  ASSERT_TRUE(r.rate());
  EXPECT_NEAR(*r.rate(), 0.2, 1e-9);
  EXPECT_EQ(RealTimeRate::text(0.2), "0.2\u00d7 real time");
  r.count(0.0, true, 1.02);  // a reset: the time went back
  EXPECT_FALSE(r.rate());
  r.count(0.5, false, 3.0);  // paused
  EXPECT_FALSE(r.rate());
}

}  // namespace
}  // namespace invfree::live
