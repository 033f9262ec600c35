// `invfree live`'s projector defaults (docs/live.md), as a class sees them: the
// window opens on compress meshed at 16 (the n_seg the panel and the benchmark line show),
// with the run's automatic colour range and the camera following the body, so that at the
// squeeze (3.75 s, the frame render's defaults were chosen on) the body spans a good part of
// the picture and is clearly coloured, not the pale tint of the fixed 0.25..4 scale. The
// old defaults (--camera fixed --color-range fixed --min-n-seg 0) are measured the same way
// and fail both: the measure tells the two apart.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include <GLFW/glfw3.h>

#include "app/live/live_app.h"
#include "app/render/camera.h"
#include "scene_io/builtin_scenes.h"
#include "tests/render/image_compare.h"
#include "tests/test_paths.h"

namespace invfree::live {
namespace {

std::string temp_dir() {
  const std::string d = ::testing::TempDir() + "/live_defaults_" + std::to_string(::getpid());
  std::filesystem::create_directories(d);
  return d;
}

// Runs `invfree ARGS`; returns its stdout, *code its exit status.
std::string run_output(const std::string& args, int* code) {
  const std::string cmd = std::string(::invfree::test::exe_path()) + " " + args + " 2>/dev/null";
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  while (size_t n = std::fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  const int status = ::pclose(p);
  *code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

// The n_seg the benchmark line reports for one frame of `invfree live ARGS`.
int shown_n_seg(const std::string& args) {
  int code = -1;
  const std::string out = run_output("live --frames 1 --bench " + args, &code);
  EXPECT_EQ(code, 0) << args << "\n" << out;
  const size_t at = out.find("n_seg ");
  if (at == std::string::npos) {
    ADD_FAILURE() << "no n_seg in the benchmark line: " << out;
    return -1;
  }
  return std::stoi(out.substr(at + 6));
}

TEST(LiveDefaults, TheWindowOpensOnAProjectorsMesh) {
  EXPECT_EQ(shown_n_seg("--scene compress"), 16);  // the scene's 4 x 4, refined
  EXPECT_EQ(shown_n_seg("--scene compress --min-n-seg 0"), 4);  // the opt-out, as render's
  EXPECT_EQ(shown_n_seg("--scene compress --set mesh.n_seg=6"), 6);  // the user's own mesh
  EXPECT_EQ(shown_n_seg("--scene compress --min-n-seg 24"), 24);
}

// What the picture's world area shows of the body: the share of the plot's pixels that are
// tinted (channels 30 or more apart: the body's colours; the stage, the ground's hatching and
// the mesh's edges are grey, a body at det F near 1 white), and the share of the tinted
// pixels that are clearly coloured (channels 60 or more apart).
struct BodyInPicture {
  double tinted = 0.0;
  double clearly_coloured = 0.0;
};

BodyInPicture measure(int frames, const std::string& args) {
  const std::string png = temp_dir() + "/squeeze.png";
  std::filesystem::remove(png);
  int code = -1;
  run_output("live --scene compress --frames " + std::to_string(frames) + " --no-panel " + args +
                 " --screenshot " + png,
             &code);
  EXPECT_EQ(code, 0) << args;
  test::RgbImage img;
  if (!test::load_png(png, &img)) {
    ADD_FAILURE() << "no screenshot " << png;
    return {};
  }
  const render::PixelRect plot = render::frame_layout(img.width, img.height).plot;
  long tinted = 0, clear = 0;
  for (int y = int(plot.y); y < int(plot.y + plot.h); ++y)
    for (int x = int(plot.x); x < int(plot.x + plot.w); ++x) {
      const std::uint8_t* p = &img.rgb[3 * (size_t(y) * img.width + x)];
      const int spread = std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]});
      if (spread < 30) continue;
      ++tinted;
      clear += spread >= 60;
    }
  BodyInPicture b;
  b.tinted = double(tinted) / (plot.w * plot.h);
  if (tinted > 0) b.clearly_coloured = double(clear) / double(tinted);
  return b;
}

TEST(LiveDefaults, TheSqueezedBodyIsClearlyColoured) {
  // t = 2 s (the quick start's picture: the ceiling pressing) and 3.75 s (the squeeze).
  for (const int frames : {200, 375}) {
    const BodyInPicture now = measure(frames, "");
    EXPECT_GE(now.tinted, 0.04) << "frame " << frames << ": too little of the body is coloured";
    EXPECT_GE(now.clearly_coloured, 0.6) << "frame " << frames << ": the body is pale";
    // The old defaults: pale on 0.25..4 (at t = 2 s not a pixel tinted).
    const BodyInPicture old = measure(frames, "--camera fixed --color-range fixed --min-n-seg 0");
    EXPECT_TRUE(old.tinted < 0.04 || old.clearly_coloured < 0.6) << "frame " << frames;
    std::printf("frame %d: %.1f%% of the picture tinted, %.0f%% of that clearly coloured (old "
                "defaults: %.1f%%, %.0f%%)\n",
                frames, 100 * now.tinted, 100 * now.clearly_coloured, 100 * old.tinted,
                100 * old.clearly_coloured);
  }
}

// The follow camera in the window: it moves with the squeezed body, a zoom with the wheel
// takes over (the view stays where the user left it while the body moves on), and F
// follows the body again.
std::unique_ptr<LiveApp> open_compress(bool follow_camera) {
  LiveOptions o;
  for (const auto& e : builtin_scenes()) {
    if (e.name == std::string_view("compress")) o.selected = static_cast<int>(o.scenes.size());
    o.scenes.push_back({std::string(e.name), *load_builtin_scene(e.name).scene});
  }
  o.follow_camera = follow_camera;
  o.vsync = false;
  std::string error;
  auto app = LiveApp::create(o, &error);
  EXPECT_TRUE(app) << error;
  return app;
}

// The share of the picture's width (between the panel and the det F panel) the body spans.
double body_width_share(const LiveApp& app, LiveController& lc) {
  const VecX& x = lc.simulation().x;
  double lo = 1e9, hi = -1e9;
  for (Eigen::Index i = 0; i + 1 < x.size(); i += 2) {
    const double px = app.to_window(Vec2(x[i], x[i + 1])).x();
    lo = std::min(lo, px);
    hi = std::max(hi, px);
  }
  const render::PixelRect plot = render::frame_layout(1280, 720).plot;
  const double panel_right = 390.0 * app.view().ui_scale;
  return (hi - lo) / (plot.x + plot.w - panel_right);
}

// At t = 2 s (the ceiling pressing) the follow camera shows the body across most of the
// picture's width; the stage camera, a third of it.
TEST(LiveDefaults, TheFollowCameraShowsTheBodyLarge) {
  auto follow = open_compress(true), stage = open_compress(false);
  ASSERT_TRUE(follow && stage);
  for (int k = 0; k < 200; ++k) {
    follow->frame();
    stage->frame();
  }
  const double followed = body_width_share(*follow, follow->controller());
  const double staged = body_width_share(*stage, stage->controller());
  EXPECT_GE(followed, 0.5);
  EXPECT_LT(staged, 0.5);
  std::printf("t = 2 s: the body spans %.0f%% of the picture's width (the whole stage: %.0f%%)\n",
              100 * followed, 100 * staged);
}

TEST(LiveDefaults, TheFollowCameraGivesWayToTheUsersZoomUntilF) {
  auto app = open_compress(true);
  ASSERT_TRUE(app);
  const Vec2 origin = Vec2::Zero();  // a world point: where the view puts it, frame by frame
  for (int k = 0; k < 50; ++k) app->frame();
  const Vec2 early = app->to_window(origin);
  for (int k = 0; k < 100; ++k) app->frame();  // the ceiling squeezes the square
  const Vec2 followed = app->to_window(origin);
  EXPECT_GT((followed - early).norm(), 1.0) << "the camera did not follow the body";

  Injection wheel;  // over the picture, right of the panel and below the body
  wheel.x = 900.0f;
  wheel.y = 680.0f;
  wheel.wheel = 1.0f;
  app->frame(&wheel);
  Injection still;
  still.x = wheel.x;
  still.y = wheel.y;
  app->frame(&still);
  const Vec2 zoomed = app->to_window(origin);
  for (int k = 0; k < 100; ++k) app->frame();  // the body moves on; the view stays
  EXPECT_LT((app->to_window(origin) - zoomed).norm(), 1e-6) << "the user's zoom was not kept";

  Injection f = still;
  f.keys = {GLFW_KEY_F};
  app->frame(&f);
  app->frame(&still);
  EXPECT_GT((app->to_window(origin) - zoomed).norm(), 1.0) << "F did not frame the body again";
}

}  // namespace
}  // namespace invfree::live
