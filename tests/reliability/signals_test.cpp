// Signals at each stage of a run (app/interrupt.h): before the first step (a
// signal that is already pending when main starts), during the steps (output_test.cpp),
// and while ffmpeg makes the movie — Ctrl-C to the whole process group as a terminal
// sends it, and SIGTERM or SIGHUP to invfree alone, which passes it on. Every time: exit
// 130 (129 after SIGHUP), one line, complete outputs only. A hang-up the parent set to
// be ignored (nohup) stays ignored.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <string>
#include <thread>

#include "app/output_files.h"
#include "tests/reliability/output_checks.h"
#include "tests/reliability/process.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

namespace fs = std::filesystem;
using namespace test;

const std::string kCsvHeader =
    "step,t,newton_iters,residual,incremental_potential,min_det_F,max_det_F,min_gap,ceiling_y,"
    "kinetic,elastic,gravitational,contact,min_self_gap,self_intersecting,wall_ms\n";

// A signal sent before the command's main has run: the child starts with it blocked, so
// it is pending when main starts, however fast this test is. The command must handle it
// like one during the run (before, a SIGTERM in the first ~0.1 s left an empty output
// directory): stop before the first step, keep step 0 complete.
void signal_before_start(int sig, int expected_code) {
  const std::string dir = fresh_dir("early_" + std::to_string(sig));
  Process p({::invfree::test::exe_path(), "simulate", "--steps", "1000", "--obj", dir + "/obj", "--csv",
             dir + "/run.csv"},
            {}, "", with_blocked(sig));
  ASSERT_GT(p.pid(), 0);
  ASSERT_EQ(::kill(p.pid(), sig), 0);
  const ProcessResult r = p.wait();
  EXPECT_EQ(r.code, expected_code) << r.err;
  EXPECT_EQ(r.err, "invfree: interrupted after step 0; outputs hold steps 0..0\n");
  EXPECT_EQ(expect_only_complete_objs(dir + "/obj", 25, 32), 1);
  EXPECT_EQ(slurp(dir + "/run.csv"), kCsvHeader);
  fs::remove_all(dir);
}

TEST(Signals, SigtermBeforeTheFirstStep) {
  signal_before_start(SIGTERM, 130);
}
TEST(Signals, SighupBeforeTheFirstStep) {
  signal_before_start(SIGHUP, 129);
}

TEST(Signals, SigintBeforeTheFirstFrame) {
  const std::string dir = fresh_dir("early_render");
  Process p({::invfree::test::exe_path(), "render", "--frames", "1000", "--size", "96x64", "--out", dir + "/f"}, {},
            "", with_blocked(SIGINT));
  ASSERT_GT(p.pid(), 0);
  ASSERT_EQ(::kill(p.pid(), SIGINT), 0);
  const ProcessResult r = p.wait();
  EXPECT_EQ(r.code, 130) << r.err;
  EXPECT_EQ(r.err, "invfree: interrupted after frame 0; the frames written are complete\n");
  EXPECT_EQ(expect_only_complete_pngs(dir + "/f"), 0);
  fs::remove_all(dir);
}

// `nohup invfree ...`: the parent ignores SIGHUP, and the run must go on through one.
TEST(Signals, IgnoredHangUpStaysIgnored) {
  const std::string dir = fresh_dir("nohup");
  Process p({::invfree::test::exe_path(), "simulate", "--steps", "100000000", "--obj", dir + "/obj"}, {},
            "trap '' HUP;");
  ASSERT_GT(p.pid(), 0);
  wait_for_files(dir + "/obj", ".obj", 10);
  ASSERT_EQ(::kill(p.pid(), SIGHUP), 0);
  wait_for_files(dir + "/obj", ".obj", 40);  // still stepping
  ASSERT_EQ(::kill(p.pid(), SIGINT), 0);
  const ProcessResult r = p.wait();
  EXPECT_EQ(r.code, 130) << r.err;
  EXPECT_GE(expect_only_complete_objs(dir + "/obj", 25, 32), 40);
  fs::remove_all(dir);
}

// True once `dir` holds a file whose name starts with `prefix` (waits at most 120 s).
bool wait_for_name(const std::string& dir, const std::string& prefix) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().filename().string().rfind(prefix, 0) == 0) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

// Renders 60 frames with --mp4 and signals once ffmpeg has opened its (temporary) movie:
// to the whole process group (a terminal's Ctrl-C) or to invfree alone.
void signal_during_movie(int sig, bool whole_group, int expected_code) {
  if (!fs::exists("/usr/bin/ffmpeg") && !fs::exists("/usr/local/bin/ffmpeg"))
    GTEST_SKIP() << "ffmpeg is not installed";
  const std::string dir = fresh_dir("movie_signal_" + std::to_string(sig)) + "/f";
  Process p({::invfree::test::exe_path(), "render", "--frames", "60", "--size", "640x480", "--mp4", "--out", dir},
            {}, "", in_own_process_group());
  ASSERT_GT(p.pid(), 0);
  ASSERT_TRUE(wait_for_name(dir, "movie.tmp")) << "ffmpeg never started";
  ASSERT_EQ(whole_group ? ::kill(-p.pid(), sig) : ::kill(p.pid(), sig), 0);
  const ProcessResult r = p.wait();
  EXPECT_EQ(r.code, expected_code) << r.err;
  EXPECT_EQ(r.err, "invfree: interrupted while making " + dir +
                       "/movie.mp4 (none written); the 60 frames are complete\n");
  EXPECT_FALSE(fs::exists(dir + "/movie.mp4"));
  EXPECT_EQ(expect_only_complete_pngs(dir), 60);  // and no temporary movie left
  fs::remove_all(fs::path(dir).parent_path());
}

TEST(Signals, CtrlCWhileFfmpegRuns) {
  signal_during_movie(SIGINT, true, 130);
}
TEST(Signals, SigtermWhileFfmpegRunsReachesIt) {
  signal_during_movie(SIGTERM, false, 130);
}
TEST(Signals, HangUpWhileFfmpegRuns) {
  signal_during_movie(SIGHUP, false, 129);
}

}  // namespace
}  // namespace invfree
