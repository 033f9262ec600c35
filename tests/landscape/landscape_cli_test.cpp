// `invfree landscape` end to end: a chart for one model, for all four, with a scene's
// triangles after some steps; one-line errors with exit 2 for bad input, exit 3 when a step
// before --step fails, and no file left behind by either.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "tests/render/image_compare.h"
#include "tests/run_command.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

using test::CommandResult;

CommandResult run(const std::string& args) {
  return test::run_command(::invfree::test::exe_path(), "landscape " + args, true);
}

std::string temp_dir(const std::string& name) {
  const std::string dir =
      ::testing::TempDir() + "/landscape_cli_" + name + "_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(LandscapeCli, WritesEachFormat) {
  const std::string dir = temp_dir("formats");
  for (const char* ext : {"png", "svg", "pdf"}) {
    const std::string out = dir + "/nh." + ext;
    const CommandResult r = run("--model neo-hookean --out " + out);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_NE(r.out.find("landscape: neo-Hookean, mu = 35.7 kPa, lambda = 143 kPa; wrote"),
              std::string::npos)
        << r.out;
    EXPECT_GT(std::filesystem::file_size(out), 1000u);
  }
  // No temporaries left beside them (written atomically).
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
    ++files;
  }
  EXPECT_EQ(files, 3);
  std::filesystem::remove_all(dir);
}

TEST(LandscapeCli, AChartWithoutDotsForParticles) {
  // The course's chapter 0 has no triangles: the landscape is drawn, no dots, and the
  // caption says why.
  const std::string dir = temp_dir("particles");
  const std::string out = dir + "/particles.png";
  const CommandResult r = run("--scene course-0-spring --step 5 --out " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("course-0-spring has no triangles"), std::string::npos) << r.out;
  test::RgbImage image;
  EXPECT_TRUE(test::load_png(out, &image));
  std::filesystem::remove_all(dir);
}

TEST(LandscapeCli, AllModelsWithAScenesTrianglesAfterSteps) {
  const std::string dir = temp_dir("scene");
  const std::string out = dir + "/all.png";
  const CommandResult r =
      run("--model all --scene compress --set material.model=linear --set material.E=1e4 --set "
          "mesh.n_seg=8 --set initial.velocity=[0,-8] --step 23 --out " +
          out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("landscape: 4 models"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("128 triangles at step 23"), std::string::npos) << r.out;
  test::RgbImage image;
  ASSERT_TRUE(test::load_png(out, &image));
  EXPECT_GT(image.width, image.height);  // four panels side by side
  // --mu and --lambda without a scene set the title's parameters.
  const CommandResult r2 = run("--model arap --mu 1000 --lambda 2000 --out " + dir + "/arap.png");
  ASSERT_EQ(r2.code, 0) << r2.err;
  EXPECT_NE(r2.out.find("mu = 1 kPa, lambda = 2 kPa"), std::string::npos) << r2.out;
  std::filesystem::remove_all(dir);
}

TEST(LandscapeCli, BadInputIsOneLineAndExitTwo) {
  const std::string dir = temp_dir("bad");
  const std::string png = dir + "/x.png";
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"--model rubber --out " + png, "unknown --model rubber"},
      {"--out " + png, "--model is required without --scene"},
      {"--model arap --out " + dir + "/x.jpg", "must end in .png, .svg or .pdf"},
      {"--model arap --out " + dir + "/x", "must end in .png, .svg or .pdf"},
      {"--model arap --format tiff --out " + png, "unknown --format tiff"},
      {"--model arap --format svg --out " + png, "does not end in .svg"},
      {"--model arap --scene compress --step -1 --out " + png, "--step"},
      {"--model arap --step 3 --out " + png, "--step is a step of a scene"},
      {"--model arap --set mesh.n_seg=4 --out " + png, "--set changes a scene"},
      {"--model arap --mu 0 --out " + png, "--mu must be > 0"},
      {"--model arap --mu nan --out " + png, "--mu"},
      {"--scene compress --mu 5 --out " + png, "with --scene use --set material.mu"},
      {"--scene nowhere --out " + png, "nowhere"},
      {"--scene compress --set mesh.n_seg=-3 --out " + png, "mesh.n_seg"},
      {"--model arap", "--out"},
  };
  for (const Case& c : cases) {
    const CommandResult r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_TRUE(test::one_line(r.err)) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(png)) << c.args;
  }
  // An existing file is not replaced without --force.
  ASSERT_EQ(run("--model arap --out " + png).code, 0);
  const CommandResult again = run("--model arap --out " + png);
  EXPECT_EQ(again.code, 2);
  EXPECT_NE(again.err.find("exists; use --force"), std::string::npos) << again.err;
  EXPECT_EQ(run("--model arap --force --out " + png).code, 0);
  std::filesystem::remove_all(dir);
}

TEST(LandscapeCli, AFailedStepIsExitThreeAndWritesNothing) {
  const std::string dir = temp_dir("failed");
  const std::string png = dir + "/x.png";
  const CommandResult r =
      run("--scene compress --set time.max_newton=1 --set time.tol=1e-14 --step 3 --out " + png);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(test::one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("step 1 failed: newton-failed"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(png));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace invfree
