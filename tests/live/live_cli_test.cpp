// `invfree live` and plain `invfree` on the command line, without a display: one line
// suggesting `invfree render` or xvfb-run and a non-zero exit, never a crash; --help
// lists every key; bad options are bad input (exit 2).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "app/live/key_bindings.h"
#include "tests/run_command.h"
#include "tests/test_paths.h"

namespace invfree::live {
namespace {

using Result = test::CommandResult;

// Runs invfree with no display at all (DISPLAY and WAYLAND_DISPLAY removed).
Result run_headless(const std::string& args) {
  return test::run_command(::invfree::test::exe_path(), args, true);
}

int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(LiveCli, WithoutADisplayOneLineAndNonZeroExit) {
  for (const char* args : {"live", "live --frames 3 --screenshot x.png", "live --bench"}) {
    const Result r = run_headless(args);
    EXPECT_EQ(r.code, 4) << args;  // the window (an output) could not be opened
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("invfree render"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("xvfb-run"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  // Plain `invfree` opens the live window only when there is a display.
  const Result plain = run_headless("");
  EXPECT_EQ(plain.code, 2);
  EXPECT_EQ(lines(plain.err), 1) << plain.err;
  EXPECT_NE(plain.err.find("invfree render"), std::string::npos) << plain.err;
}

TEST(LiveCli, HelpListsEveryKey) {
  const Result r = run_headless("live --help");
  EXPECT_EQ(r.code, 0);
  for (const auto& b : key_bindings()) {
    EXPECT_NE(r.out.find(b.key_name), std::string::npos) << b.key_name;
    EXPECT_NE(r.out.find(b.description), std::string::npos) << b.description;
  }
  for (const auto& m : mouse_bindings()) EXPECT_NE(r.out.find(m.gesture), std::string::npos);
  for (const char* opt : {"--frames", "--screenshot", "--bench", "--set", "--scene", "--record",
                          "--color-by", "--stress-glyphs", "--landscape", "--select-triangle"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(LiveCli, BadInputIsRejectedBeforeAnyWindow) {
  const std::string dir = ::testing::TempDir();
  { std::ofstream(dir + "/live_bad_nu.toml") << "[material]\nE = 1e5\nnu = 0.7\n"; }
  const std::vector<std::string> cases = {"live --scene nosuchscene",
                                          "live --set material.nu=0.5",
                                          "live --frames -1",
                                          "live --size 10x10",
                                          "live --size big",
                                          "live " + dir + "/live_bad_nu.toml",
                                          "live --steps-per-frame 0",
                                          "live --color-by nosuchfield",
                                          "live --select-triangle 100000000",
                                          "live --select-triangle -1"};
  for (const std::string& args : cases) {
    const Result r = run_headless(args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << ": " << r.err;
  }
}

TEST(LiveCli, OutputPathsAreCheckedBeforeAnyWindow) {
  // Checked at launch, by render's rules and exit codes (docs/cli.md), not after the run:
  // without a display these fail on the path, not on the missing window (exit 4).
  const std::string dir = ::testing::TempDir() + "/live_paths_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir + "/full");
  { std::ofstream(dir + "/full/frame_000000.png") << "x"; }
  { std::ofstream(dir + "/a_file") << "x"; }
  Result r = run_headless("live --record " + dir + "/full");
  EXPECT_EQ(r.code, 2) << r.err;  // as `render --out` a non-empty directory
  EXPECT_NE(r.err.find("not empty"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--force"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  // --force is accepted (the run then fails only on the missing display).
  r = run_headless("live --force --record " + dir + "/full");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("xvfb-run"), std::string::npos) << r.err;
  // An existing screenshot is replaced only with --force, as every output (docs/outputs.md).
  r = run_headless("live --frames 3 --screenshot " + dir + "/a_file");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("exists; use --force"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  r = run_headless("live --frames 3 --force --screenshot " + dir + "/a_file");
  EXPECT_EQ(r.code, 4) << r.err;  // accepted; then no display
  // A path that names a directory (ends in '/') is no file name.
  r = run_headless("live --frames 3 --screenshot " + dir + "/new_dir/");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("names a directory"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/new_dir")) << "nothing made for a refused path";
  // A directory that cannot be made (a file is in the way), for either output.
  for (const std::string& args : {"live --record " + dir + "/a_file/rec",
                                  "live --frames 3 --screenshot " + dir + "/a_file/x.png"}) {
    r = run_headless(args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(r.err.find("xvfb-run"), std::string::npos) << args << ": " << r.err;
    EXPECT_NE(r.err.find(dir + "/a_file"), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << ": " << r.err;
  }
}

}  // namespace
}  // namespace invfree::live
