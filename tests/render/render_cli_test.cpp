// `invfree render` end to end: frames on disk (frame 0 is the initial state, pixel for
// pixel the golden), no partial files, refusal of a non-empty directory, bad input,
// --mp4 with and without ffmpeg, a failing step. Runs with DISPLAY unset.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/render/image_compare.h"
#include "tests/run_command.h"
#include "tests/test_paths.h"

namespace {

namespace fs = std::filesystem;

using invfree::test::CommandResult;
using invfree::test::slurp;

// Runs `invfree ARGS` without a display (and with `env` first, if given).
CommandResult run(const std::string& args, const std::string& env = "") {
  return invfree::test::run_command(::invfree::test::exe_path(), args, true, env);
}

std::string fresh_dir(const std::string& name) {
  const std::string dir =
      ::testing::TempDir() + "/render_cli_" + name + "_" + std::to_string(::getpid());
  fs::remove_all(dir);
  return dir;
}

std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(RenderCli, WritesFramesAndFrameZeroIsTheInitialState) {
  const std::string dir = fresh_dir("frames");
  // The golden's picture: the scene's own mesh, the fixed camera and colour scale.
  const CommandResult r =
      run("render --scene compress --frames 3 --size 960x540 --min-n-seg 0 --camera fixed "
          "--color-range fixed --out " +
          dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // no progress when stderr is not a terminal
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_NE(r.out.find("3 frames 960x540"), std::string::npos) << r.out;
  // Exactly the frames: no temporary or partial file left behind.
  EXPECT_EQ(files_in(dir),
            (std::vector<std::string>{"frame_000000.png", "frame_000001.png", "frame_000002.png"}));
  invfree::test::RgbImage frame0;
  ASSERT_TRUE(invfree::test::load_png(dir + "/frame_000000.png", &frame0));
  const std::string message =
      invfree::test::check_golden(frame0, "compress_t0", ::invfree::test::golden_dir(),
                                  std::string(::invfree::test::golden_failure_dir()) + "/cli");
  if (std::getenv("INVFREE_UPDATE_GOLDENS") == nullptr) {
    EXPECT_EQ(message, "");
  }
  invfree::test::RgbImage frame2;
  ASSERT_TRUE(invfree::test::load_png(dir + "/frame_000002.png", &frame2));
  EXPECT_NE(frame0.rgb, frame2.rgb);  // the square moved (and the time label changed)
}

TEST(RenderCli, ParticlesWithoutTrianglesRenderInEveryColouring) {
  // The course's chapter 0 (no triangles): frames with the particles drawn, the summary
  // says "no triangles" (no det F of none), and every colouring, --camera follow and the
  // glyphs run; --select-triangle has no triangle to name.
  for (const std::string scene : {"course-0-free-fall", "course-0-spring"}) {
    for (const std::string extra :
         {"", " --color-by psi --stress-glyphs --camera follow --color-range frame"}) {
      const std::string dir = fresh_dir("particles");
      const CommandResult r = run("render --scene " + scene + " --frames 3 --steps-per-frame 10 " +
                                  "--size 320x180 --out " + dir + extra);
      ASSERT_EQ(r.code, 0) << scene << extra << "\n" << r.err;
      EXPECT_NE(r.out.find("no triangles"), std::string::npos) << r.out;
      EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
      invfree::test::RgbImage frame;
      ASSERT_TRUE(invfree::test::load_png(dir + "/frame_000002.png", &frame));
      long blue = 0;  // the particles' dots (render::kParticleColor)
      for (size_t k = 0; k + 2 < frame.rgb.size(); k += 3)
        blue += frame.rgb[k + 2] > 150 && frame.rgb[k] < 80 && frame.rgb[k + 1] < 110;
      EXPECT_GT(blue, 10) << scene << extra;
    }
  }
  const CommandResult selected =
      run("render --scene course-0-spring --frames 1 "
          "--select-triangle 0 --out " +
          fresh_dir("particles_selected"));
  EXPECT_EQ(selected.code, 2) << selected.err;
}

TEST(RenderCli, RefusesANonEmptyDirectoryUnlessForced) {
  const std::string dir = fresh_dir("force");
  const CommandResult first = run("render --frames 1 --size 320x180 --out " + dir);
  ASSERT_EQ(first.code, 0) << first.err;
  const CommandResult again = run("render --frames 2 --size 320x180 --out " + dir);
  EXPECT_EQ(again.code, 2);
  EXPECT_EQ(std::count(again.err.begin(), again.err.end(), '\n'), 1) << again.err;
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
  EXPECT_EQ(files_in(dir).size(), 1u);  // untouched
  const CommandResult forced = run("render --frames 2 --size 320x180 --force --out " + dir);
  EXPECT_EQ(forced.code, 0) << forced.err;
  EXPECT_EQ(files_in(dir).size(), 2u);
}

TEST(RenderCli, BadInputIsOneLineAndExitTwo) {
  const std::string dir = fresh_dir("bad");
  for (const std::string args :
       {"--size 12x12", "--size wide", "--size 1280x", "--frames 0", "--steps-per-frame 0",
        "--scene nosuchscene", "--set material.nu=0.7", "--fps 0", "--color-by vonmises",
        "--color-by", "--select-triangle 32", "--select-triangle -1",
        "--select-triangle 9999999999"}) {
    const CommandResult r = run("render --out " + dir + " " + args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("invfree: ", 0), 0u) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir) && !fs::is_empty(dir));
}

TEST(RenderCli, UnknownColoringNamesTheChoices) {
  const std::string dir = fresh_dir("colorby");
  const CommandResult r = run("render --frames 1 --color-by vonmises --out " + dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (const char* word : {"--color-by", "vonmises", "det-f", "psi", "stress", "clamped"})
    EXPECT_NE(r.err.find(word), std::string::npos) << word << ": " << r.err;
  // The default mesh has 32 triangles: 0..31.
  const CommandResult out_of_range = run("render --frames 1 --select-triangle 32 --out " + dir);
  EXPECT_EQ(out_of_range.code, 2);
  EXPECT_NE(out_of_range.err.find("--select-triangle: 32 is out of range"), std::string::npos)
      << out_of_range.err;
  EXPECT_NE(out_of_range.err.find("0..31"), std::string::npos) << out_of_range.err;
  EXPECT_FALSE(fs::exists(dir));  // refused before anything was written
  const CommandResult help = run("render --help");
  for (const char* word :
       {"--color-by", "{det-f,psi,stress,clamped}", "--stress-glyphs", "--select-triangle"})
    EXPECT_NE(help.out.find(word), std::string::npos) << word;
}

TEST(RenderCli, EveryColoringWithGlyphsAndASelectionWritesItsFrames) {
  // Each --color-by on a compressing square, with the glyphs and an outlined triangle: the
  // frames are written, and each colouring's last frame differs from det F's.
  const auto last_frame = [](const std::string& extra, const std::string& name) {
    const std::string dir = fresh_dir(name);
    const CommandResult r =
        run("render --frames 2 --steps-per-frame 100 --size 320x180 " + extra + " --out " + dir);
    EXPECT_EQ(r.code, 0) << extra << "\n" << r.err;
    invfree::test::RgbImage frame;
    EXPECT_TRUE(invfree::test::load_png(dir + "/frame_000001.png", &frame)) << extra;
    return frame;
  };
  const auto det_f = last_frame("", "detf");
  for (const std::string field : {"psi", "stress", "clamped"}) {
    const auto frame =
        last_frame("--color-by " + field + " --stress-glyphs --select-triangle 5", field);
    EXPECT_NE(frame.rgb, det_f.rgb) << field;
  }
  // det-f named is the default.
  EXPECT_EQ(last_frame("--color-by det-f", "detf_named").rgb, det_f.rgb);
}

TEST(RenderCli, Mp4WithoutFfmpegSaysSoBeforeRendering) {
  const std::string dir = fresh_dir("noffmpeg");
  const CommandResult r =
      run("render --frames 2 --size 320x180 --mp4 --out " + dir, "PATH=/nonexistent");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("ffmpeg"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/frame_000000.png"));
}

TEST(RenderCli, Mp4WithFfmpegHasEvenDimensions) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1 && command -v ffprobe >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffmpeg is not installed";
  const std::string dir = fresh_dir("mp4");
  const CommandResult r = run("render --frames 4 --size 321x181 --mp4 --fps 25 --out " + dir);
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir + "/movie.mp4"));
  const std::string probe = dir + "/probe.txt";
  ASSERT_EQ(std::system(("ffprobe -v error -select_streams v:0 -show_entries "
                         "stream=width,height,pix_fmt,nb_frames "
                         "-of default=noprint_wrappers=1 " +
                         dir + "/movie.mp4 >" + probe)
                            .c_str()),
            0);
  const std::string info = slurp(probe);
  EXPECT_NE(info.find("width=322"), std::string::npos) << info;
  EXPECT_NE(info.find("height=182"), std::string::npos) << info;
  EXPECT_NE(info.find("pix_fmt=yuv420p"), std::string::npos) << info;
  EXPECT_NE(info.find("nb_frames=4"), std::string::npos) << info;
}

TEST(RenderCli, LectureDefaultPlaysInRealTimeNearThirtyFramesAndGifToo) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1 && command -v ffprobe >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffmpeg is not installed";
  // h = 0.01 s: 3 steps per frame play in real time at 33.3 frames/s.
  const std::string dir = fresh_dir("lecture");
  const CommandResult r = run("render --frames 5 --size 160x90 --mp4 --gif --out " + dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("12 steps, t = 0.120 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("movie: 33.33 frames/s, 3 step(s)/frame, encoded in"), std::string::npos)
      << r.out;
  ASSERT_TRUE(fs::exists(dir + "/movie.mp4"));
  ASSERT_TRUE(fs::exists(dir + "/movie.gif"));
  const std::string probe = dir + "/probe.txt";
  ASSERT_EQ(std::system(("ffprobe -v error -select_streams v:0 -show_entries stream=codec_name "
                         "-of default=noprint_wrappers=1 " +
                         dir + "/movie.gif >" + probe)
                            .c_str()),
            0);
  EXPECT_NE(slurp(probe).find("codec_name=gif"), std::string::npos) << slurp(probe);
  // Given steps per frame are kept.
  const std::string dir1 = fresh_dir("lecture1");
  const CommandResult r1 =
      run("render --frames 3 --size 160x90 --mp4 --steps-per-frame 1 --out " + dir1);
  EXPECT_NE(r1.out.find("movie: 100 frames/s, 1 step(s)/frame"), std::string::npos) << r1.out;
}

// Pixels of the failure mark's red (frame_vertices.cpp's kFailureInk, 0.80 0.04 0.06).
long failure_red_pixels(const invfree::test::RgbImage& image) {
  long n = 0;
  for (size_t i = 0; i + 2 < image.rgb.size(); i += 3)
    n += std::abs(image.rgb[i] - 204) <= 3 && image.rgb[i + 1] <= 14 && image.rgb[i + 2] <= 19;
  return n;
}

TEST(RenderCli, FailedStepKeepsTheFramesBeforeItAndMarksTheLastOne) {
  const std::string dir = fresh_dir("fail");
  const CommandResult r = run(
      "render --frames 5 --size 320x180 --set time.max_newton=1 --set time.tol=1e-14 --out " + dir);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("step 1 failed"), std::string::npos) << r.err;
  // Frame 0, then the same (last good) state once more, marked as failed.
  ASSERT_EQ(files_in(dir), (std::vector<std::string>{"frame_000000.png", "frame_000001.png"}));
  invfree::test::RgbImage good, failed;
  ASSERT_TRUE(invfree::test::load_png(dir + "/frame_000000.png", &good));
  ASSERT_TRUE(invfree::test::load_png(dir + "/frame_000001.png", &failed));
  EXPECT_EQ(failure_red_pixels(good), 0);
  // The border (at least 3 px on four sides of a ~200 x 180 world) and the banner.
  EXPECT_GT(failure_red_pixels(failed), 3 * (2 * 180 + 2 * 150));
}

// Issue 32 item 12: render and simulate give det F one meaning, over every step of the
// run (render saw only the frames' states: every third step here).
TEST(RenderCli, DetFRangeIsOverEveryStepAsSimulateGivesIt) {
  const std::string dir = fresh_dir("detf");
  const CommandResult r =
      run("render --frames 31 --steps-per-frame 3 --size 160x90 --min-n-seg 0 "
          "--set material.model=linear --set material.E=1e4 --set mesh.n_seg=8 "
          "--set initial.velocity=[0,-8] --out " +
          dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const CommandResult sim =
      run("simulate --steps 90 --set material.model=linear --set material.E=1e4 --set mesh.n_seg=8 "
          "--set initial.velocity=[0,-8]");
  ASSERT_EQ(sim.code, 0) << sim.err;
  const size_t at = sim.out.find("det F in [");
  ASSERT_NE(at, std::string::npos) << sim.out;
  const std::string range = sim.out.substr(at, sim.out.find('\n', at) - at);
  EXPECT_NE(range.find("over steps 0..90"), std::string::npos) << range;
  EXPECT_NE(r.out.find(range), std::string::npos) << r.out << "\nsimulate: " << range;
}

// The share of the plot's pixels (the left `plot_fraction` of the frame) whose colour is
// clearly a colour (max - min channel > 60): the det F fills, not the grey stage, the white
// body at det F = 1 or the pale tints of a fixed 0.25..4 scale.
double colored_share(const invfree::test::RgbImage& image, double plot_fraction) {
  long colored = 0, all = 0;
  const int w = static_cast<int>(plot_fraction * image.width);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < w; ++x, ++all) {
      const std::uint8_t* p = &image.rgb[3 * (static_cast<size_t>(y) * image.width + x)];
      colored += std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) > 60;
    }
  return double(colored) / all;
}

// Issue 32 item 4: the default picture carries to the back of a lecture room. At t = 2 s
// (the squeeze) the default render of the default scene is clearly coloured over a good
// part of the world (the fixed scale left it pale: no pixel clearly coloured; the whole
// stage left 60% of it empty).
TEST(RenderCli, DefaultPictureIsColouredAndOnTheBody) {
  const std::string dir = fresh_dir("projector");
  const CommandResult r = run("render --frames 201 --size 320x180 --out " + dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("mesh n_seg 4 -> 16"), std::string::npos) << r.out;
  invfree::test::RgbImage squeeze;
  ASSERT_TRUE(invfree::test::load_png(dir + "/frame_000200.png", &squeeze));
  EXPECT_GT(colored_share(squeeze, 0.6), 0.08);  // measured 0.11 (the old default: 0)
  const std::string fixed_dir = fresh_dir("projector_fixed");
  ASSERT_EQ(run("render --frames 201 --size 320x180 --color-range fixed --camera fixed "
                "--min-n-seg 0 --out " +
                fixed_dir)
                .code,
            0);
  invfree::test::RgbImage before;
  ASSERT_TRUE(invfree::test::load_png(fixed_dir + "/frame_000200.png", &before));
  EXPECT_LT(colored_share(before, 0.6), 0.01);  // the old default, for contrast (measured 0)
}

// Issue 32 item 4: without --frames the movie ends when nothing moves any more (compress:
// the ceiling stops at t = 2.6 s), and says so; it used to run 300 frames whatever
// happened, 70% of a 9-s movie static.
TEST(RenderCli, DefaultRunEndsWhenNothingMovesAndSaysSo) {
  const std::string dir = fresh_dir("settled");
  const CommandResult r =
      run("render --size 160x90 --min-n-seg 0 --steps-per-frame 3 --out " + dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const size_t at = r.out.find("render: ended 0.50 s after nothing moved any more (t = ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const double settled = std::stod(r.out.substr(r.out.find("(t = ", at) + 5));
  EXPECT_GE(settled, 2.6);  // not before the ceiling stopped
  EXPECT_LT(settled, 6.0);
  const size_t frames = files_in(dir).size();
  EXPECT_NEAR(double(frames - 1) * 0.03, settled + 0.5, 0.031) << r.out;
  // A scene that never comes to rest stops at the limit and says why.
  const std::string fall = fresh_dir("falling");
  const CommandResult f = run("render --size 160x90 --scene course-0-free-fall --out " + fall);
  ASSERT_EQ(f.code, 0) << f.err;
  EXPECT_NE(f.out.find("render: stopped at the limit of"), std::string::npos) << f.out;
  EXPECT_NE(f.out.find("still moved"), std::string::npos) << f.out;
}

}  // namespace
