// `invfree modes` end to end (app/modes/modes_command.cpp): the CSV against linear.py's
// eigenvalues, one PNG per mode, the movie with --mp4 (when ffmpeg is installed), and bad
// input refused with one line and exit 2 before anything is written.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/run_command.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

namespace fs = std::filesystem;

test::CommandResult run(const std::string& args) {
  return test::run_command(test::exe_path(), "modes " + args, true);
}

std::string fresh_dir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/invfree_modes_" + name;
  fs::remove_all(dir);
  return dir;
}

bool is_png(const std::string& path) {
  const std::string bytes = test::slurp(path);
  return bytes.size() > 1000 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}

// The directory holds nothing (or does not exist): a refused run wrote nothing.
bool empty_or_missing(const std::string& dir) {
  return !fs::exists(dir) || fs::is_empty(dir);
}

TEST(ModesCommand, WritesLinearPyEigenvaluesAndAPicturePerMode) {
  const std::string dir = fresh_dir("quad");
  // The scene's [modes] element = "quad" is linear.py's; --element is not needed.
  const auto r = run("--scene modes-cantilever --count 8 --size 320x240 --out " + dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("modes-cantilever: 8 modes (quad elements, 360 free degrees of freedom)"),
            std::string::npos)
      << r.out;
  const auto rows = test::read_csv(dir + "/modes.csv");
  ASSERT_EQ(rows.size(), 9u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"mode", "eigenvalue", "omega", "frequency"}));
  std::ifstream ref(std::string(test::source_dir()) + "/tests/data/course/modes-cantilever.txt");
  std::vector<double> reference;
  for (std::string line; std::getline(ref, line);)
    if (!line.empty() && line[0] != '#') reference.push_back(std::stod(line));
  ASSERT_EQ(reference.size(), 8u);
  for (int k = 0; k < 8; ++k) {
    ASSERT_EQ(rows[k + 1].size(), 4u);
    EXPECT_EQ(rows[k + 1][0], std::to_string(k + 1));
    const double lambda = std::stod(rows[k + 1][1]), omega = std::stod(rows[k + 1][2]),
                 f = std::stod(rows[k + 1][3]);
    EXPECT_NEAR(lambda / reference[k], 1.0, 1e-8) << "mode " << k + 1;
    EXPECT_NEAR(omega, std::sqrt(lambda), 1e-12 * omega);
    EXPECT_NEAR(f, omega / (2 * M_PI), 1e-12 * f);
    char name[32];
    std::snprintf(name, sizeof name, "/mode_%02d.png", k + 1);
    EXPECT_TRUE(is_png(dir + name)) << name;
  }
  EXPECT_FALSE(fs::exists(dir + "/mode_09.png"));
  EXPECT_FALSE(fs::exists(dir + "/modes.mp4"));
  EXPECT_FALSE(fs::exists(dir + "/.invfree.lock"));
  // --element overrides the scene's element.
  const auto triangles = run("--scene modes-cantilever --element triangle --count 1 --size "
                             "320x240 --out " + fresh_dir("override"));
  ASSERT_EQ(triangles.code, 0) << triangles.err;
  EXPECT_NE(triangles.out.find("(triangle elements"), std::string::npos) << triangles.out;
  // A second run into the same directory needs --force.
  const auto again = run("--scene modes-cantilever --count 2 --size 320x240 --out " + dir);
  EXPECT_EQ(again.code, 2);
  EXPECT_TRUE(test::one_line(again.err)) << again.err;
  EXPECT_NE(again.err.find("not empty"), std::string::npos) << again.err;
}

TEST(ModesCommand, FreeBodyReportsItsRigidModes) {
  const std::string dir = fresh_dir("free");
  const auto r = run("--scene compress --count 4 --size 320x240 --out " + dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("3 rigid (eigenvalue about 0)"), std::string::npos) << r.out;
  const auto rows = test::read_csv(dir + "/modes.csv");
  ASSERT_EQ(rows.size(), 5u);
  const double fourth = std::stod(rows[4][1]);
  EXPECT_GT(fourth, 0.0);
  for (int k = 1; k <= 3; ++k) EXPECT_LT(std::abs(std::stod(rows[k][1])), 1e-8 * fourth);
}

TEST(ModesCommand, MovieWithMp4) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffmpeg is not installed";
  const std::string dir = fresh_dir("mp4");
  const auto r = run("--scene modes-cantilever --count 2 --size 160x120 --mp4 --out " + dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(fs::file_size(dir + "/modes.mp4"), 1000u);
  // Only the outputs: the frames' folder is gone.
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_TRUE(e.is_regular_file()) << e.path();
  }
  EXPECT_EQ(files, 4);  // modes.csv, mode_01.png, mode_02.png, modes.mp4
}

TEST(ModesCommand, BadInputIsOneLineAndExit2WithNothingWritten) {
  struct Case {
    std::string args, says;
  };
  const std::string file = ::testing::TempDir() + "/invfree_modes_a_file";
  std::ofstream(file) << "x";
  const std::vector<Case> cases = {
      {"--scene modes-cantilever --count 400", "must be 1 to 359"},
      {"--scene modes-cantilever --element quad --count 360", "360 free degrees of freedom"},
      {"--scene modes-cantilever --count 0", "--count"},
      {"--scene modes-cantilever --count -3", "--count"},
      {"--scene no-such-scene", "no-such-scene"},
      {"--scene course-1-mass-spring", "mass-spring"},
      {"--scene ring --element quad", "no partner"},
      {"--scene compress --element hexahedron", "--element"},
      {"--scene compress --scale nan", "--scale"},
      {"--scene compress --size 10x10", "--size"},
  };
  for (const Case& c : cases) {
    const std::string dir = fresh_dir("bad");
    const auto r = run(c.args + " --out " + dir);
    EXPECT_EQ(r.code, 2) << c.args << ": " << r.err;
    EXPECT_TRUE(test::one_line(r.err)) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << ": " << r.err;
    EXPECT_TRUE(empty_or_missing(dir)) << c.args;
  }
  // --out names a file.
  const auto r = run("--scene compress --count 2 --out " + file);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_TRUE(test::one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("not a directory"), std::string::npos) << r.err;
  // An output directory under a file cannot be created: exit 4 (an output that cannot be
  // written, docs/outputs.md), one line naming it.
  const auto w = run("--scene compress --count 2 --out " + file + "/sub");
  EXPECT_EQ(w.code, 4) << w.err;
  EXPECT_TRUE(test::one_line(w.err)) << w.err;
  EXPECT_NE(w.err.find(file + "/sub"), std::string::npos) << w.err;
}

}  // namespace
}  // namespace invfree
