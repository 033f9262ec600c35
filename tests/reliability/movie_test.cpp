// The movie and the numbers behind it: `render --force --mp4` into a directory
// holding more and larger frames of an older run makes the movie from this run's frames
// only; a frame-rate flag that is not finite or out of range, and a real-time rate
// 1 / (h * steps-per-frame) outside 0.1-1000 frames/s with --mp4, are refused (exit 2)
// before the first frame.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/reliability/output_checks.h"
#include "tests/reliability/process.h"

namespace invfree {
namespace {

namespace fs = std::filesystem;
using namespace test;

bool have_ffmpeg() {
  return fs::exists("/usr/bin/ffmpeg") && fs::exists("/usr/bin/ffprobe");
}

TEST(Movie, ForceMakesTheMovieFromThisRunsFramesOnly) {
  if (!have_ffmpeg()) GTEST_SKIP() << "ffmpeg/ffprobe are not installed";
  const std::string dir = fresh_dir("movie_force") + "/f";
  ProcessResult r = run_invfree({"render", "--frames", "20", "--size", "320x240", "--out", dir});
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_invfree(
      {"render", "--frames", "5", "--size", "160x120", "--mp4", "--force", "--out", dir});
  ASSERT_EQ(r.code, 0) << r.err;
  // Frames and size as ffmpeg decodes them.
  r = Process({"/usr/bin/ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
               "-show_entries", "stream=width,height,nb_read_frames", "-of", "csv=p=0",
               dir + "/movie.mp4"})
          .wait();
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "160,120,5\n") << "the movie must hold this run's 5 frames of 160x120";
  EXPECT_TRUE(fs::exists(dir + "/frame_000019.png")) << "--force removes nothing";
  fs::remove_all(fs::path(dir).parent_path());
}

// `render ARGS --out DIR` exits 2 with one line containing `why`, and no frame is drawn.
void expect_refused(const std::vector<std::string>& args, const std::string& why) {
  const std::string dir = fresh_dir("movie_numbers") + "/f";
  std::vector<std::string> full = {"render", "--frames", "3", "--size", "64x64", "--out", dir};
  full.insert(full.end(), args.begin(), args.end());
  const ProcessResult r = run_invfree(full);
  std::string shown;
  for (const auto& a : args) shown += a + " ";
  EXPECT_EQ(r.code, 2) << shown << ": " << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find(why), std::string::npos) << shown << ": " << r.err;
  EXPECT_FALSE(fs::exists(dir + "/frame_000000.png")) << shown;
  fs::remove_all(fs::path(dir).parent_path());
}

TEST(MovieNumbers, FrameRateFlagMustBeFiniteAndInRange) {
  for (const char* fps : {"nan", "NaN", "-nan", "inf", "-inf", "1e999", "0.05", "1001", "0"})
    expect_refused({"--fps", fps}, "--fps");
  // bench --fps too (a NaN budget would make every size "fit").
  const ProcessResult r = run_invfree(
      {"bench", "--sizes", "4", "--steps", "1", "--fps", "nan", "--out", fresh_dir("bench_nan")});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--fps"), std::string::npos) << r.err;
}

TEST(MovieNumbers, RealTimeFrameRateMustBeInRange) {
  if (!have_ffmpeg()) GTEST_SKIP() << "ffmpeg is not installed (--mp4 is refused before this)";
  const std::string why = "frame rate 1 / (h * steps-per-frame)";
  expect_refused({"--mp4", "--set", "time.h=1e-12", "--steps-per-frame", "1"},
                 why + " = 1e+12 frames/s");
  expect_refused({"--mp4", "--set", "time.h=1e-6", "--steps-per-frame", "1"},
                 why + " = 1e+06 frames/s");
  // The lecture default's steps per frame (near 30 frames/s) stop at the flag's maximum.
  expect_refused({"--mp4", "--set", "time.h=1e-12"}, why + " = 1e+06 frames/s");
  expect_refused({"--mp4", "--set", "time.h=0.5", "--steps-per-frame", "100"},
                 why + " = 0.02 frames/s");
  // An explicit --fps makes any h fine (one step per frame: 1e6 frames/s of simulated time,
  // refused above without it), and without --mp4 the rate does not matter. The lecture
  // default at h = 1e-6 picks 33,333 steps per frame (real time at 30 frames/s) and runs;
  // two frames keep it to one frame's steps (a minute of CI's sanitize stage went to three).
  for (const std::vector<std::string>& ok :
       {std::vector<std::string>{"--mp4", "--set", "time.h=1e-6", "--steps-per-frame", "1", "--fps",
                                 "30"},
        std::vector<std::string>{"--mp4", "--set", "time.h=1e-6"},  // 33,333 steps/frame
        std::vector<std::string>{"--set", "time.h=1e-6", "--steps-per-frame", "1"}}) {
    const std::string dir = fresh_dir("movie_ok") + "/f";
    // The scene's own 4x4 mesh (--min-n-seg 0): the rate is the point, not the picture, and
    // the picture's 16x16 made the 33,333 steps 230 s of the sanitize stage.
    std::vector<std::string> args = {"render", "--frames", "2",   "--size", "64x64",
                                     "--min-n-seg", "0", "--out", dir};
    args.insert(args.end(), ok.begin(), ok.end());
    const ProcessResult r = run_invfree(args);
    EXPECT_EQ(r.code, 0) << r.err;
    fs::remove_all(fs::path(dir).parent_path());
  }
}

}  // namespace
}  // namespace invfree
