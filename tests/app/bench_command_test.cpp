// `invfree bench`: writes a CSV row per size with consistent columns and a PNG chart,
// reports the speed-up against the reference demo, and rejects bad sizes with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "scene/scene.h"
#include "scene_io/builtin_scenes.h"
#include "tests/reliability/process.h"

namespace invfree {
namespace {

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string item; std::getline(in, item, sep);) out.push_back(item);
  if (!line.empty() && line.back() == sep) out.push_back("");  // an empty last cell
  return out;
}

TEST(BenchCommand, WritesTheTableAndTheChart) {
  const std::string dir = ::testing::TempDir() + "/bench_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  const test::ProcessResult r = test::run_invfree(
      {"bench", "--sizes", "2,4,6", "--steps", "20", "--out", dir, "--threads", "2"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("x the reference"), std::string::npos)
      << "n_seg 4 is a reference size: " << r.out;
  EXPECT_NE(r.out.find("fitted slope"), std::string::npos) << r.out;

  std::istringstream csv(test::slurp(dir + "/bench.csv"));
  std::string header;
  ASSERT_TRUE(std::getline(csv, header));
  const auto columns = split(header, ',');
  ASSERT_EQ(columns.front(), "n_seg");
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(csv, line);) rows.push_back(split(line, ','));
  ASSERT_EQ(rows.size(), 3u);
  auto col = [&](const std::string& name) {
    for (std::size_t k = 0; k < columns.size(); ++k)
      if (columns[k] == name) return k;
    ADD_FAILURE() << "no column " << name;
    return std::size_t{0};
  };
  const int sizes[3] = {2, 4, 6};
  for (int k = 0; k < 3; ++k) {
    const auto& row = rows[k];
    ASSERT_EQ(row.size(), columns.size());
    const int n = sizes[k];
    EXPECT_EQ(std::stoi(row[col("n_seg")]), n);
    EXPECT_EQ(std::stoi(row[col("nodes")]), (n + 1) * (n + 1));
    EXPECT_EQ(std::stoi(row[col("triangles")]), 2 * n * n);
    EXPECT_EQ(std::stoi(row[col("dofs")]), 2 * (n + 1) * (n + 1) + 1);
    EXPECT_EQ(std::stoi(row[col("steps")]), 20);
    const double mean = std::stod(row[col("mean_ms")]), median = std::stod(row[col("median_ms")]);
    EXPECT_GT(mean, 0.0);
    EXPECT_GT(median, 0.0);
    // The split is a part of the mean: never more than the whole.
    const double parts = std::stod(row[col("assembly_ms")]) + std::stod(row[col("factor_ms")]) +
                         std::stod(row[col("solve_ms")]) + std::stod(row[col("line_search_ms")]);
    EXPECT_LE(parts, mean * 1.0001 + 1e-6);
    const double newton = std::stod(row[col("newton_per_step")]);
    EXPECT_GE(newton, 1.0);  // every step takes at least one Newton step
    // The worst step: a whole number of iterations, at least the mean, at most the scene's
    // cap, at one of the steps that ran.
    const int worst = std::stoi(row[col("newton_worst")]);
    const int worst_step = std::stoi(row[col("newton_worst_step")]);
    EXPECT_GE(worst, newton);
    EXPECT_LE(worst, load_builtin_scene("compress").scene->max_newton);
    EXPECT_GE(worst_step, 1);
    EXPECT_LE(worst_step, 20);
  }
  const std::string png = test::slurp(dir + "/bench.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  std::filesystem::remove_all(dir);
}

// A meshed shape (issue 27): the ring at three n_seg, each row with its meshing time
// (mesh_ms, meshed cold: not the cache's copy) and finer meshes for larger n_seg.
TEST(BenchCommand, ARingGetsItsMeshingTime) {
  const std::string dir = ::testing::TempDir() + "/bench_ring_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  const test::ProcessResult r = test::run_invfree({"bench", "--scene", "ring", "--sizes", "8,16,32",
                                                   "--steps", "3", "--out", dir, "--threads", "2"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("mesh_ms"), std::string::npos) << r.out;
  std::istringstream csv(test::slurp(dir + "/bench.csv"));
  std::string header;
  ASSERT_TRUE(std::getline(csv, header));
  const auto columns = split(header, ',');
  const auto col = std::find(columns.begin(), columns.end(), "mesh_ms") - columns.begin();
  const auto tri = std::find(columns.begin(), columns.end(), "triangles") - columns.begin();
  ASSERT_LT(col, static_cast<long>(columns.size()));
  int last_triangles = 0;
  int rows = 0;
  for (std::string line; std::getline(csv, line); ++rows) {
    const auto row = split(line, ',');
    ASSERT_EQ(row.size(), columns.size());
    EXPECT_GT(std::stod(row[col]), 0.0) << line;
    EXPECT_GT(std::stoi(row[tri]), last_triangles) << line;
    last_triangles = std::stoi(row[tri]);
  }
  EXPECT_EQ(rows, 3);
  std::filesystem::remove_all(dir);
}

TEST(BenchCommand, BadSizesAreBadInput) {
  for (const char* sizes : {"4,x", "0", "4,,8", "-3", "99999999"}) {
    const test::ProcessResult r =
        test::run_invfree({"bench", "--sizes", sizes, "--out", ::testing::TempDir()});
    EXPECT_EQ(r.code, 2) << sizes;
    EXPECT_NE(r.err.find("--sizes"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
  }
}

// --threads LIST (issue 30): every size at every thread count, one row each, with the
// speed-up of the median step against the smallest count and the efficiency; the runs leave
// bit-identical positions after every step (n_seg 48 has two triangle blocks, so its energy
// and gradient really split over the threads; n_seg 4 runs inline).
TEST(BenchCommand, AThreadListRunsEverySizeAtEveryCount) {
  const std::string dir = ::testing::TempDir() + "/bench_threads_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  const test::ProcessResult r = test::run_invfree(
      {"bench", "--sizes", "4,48", "--steps", "4", "--out", dir, "--threads", "2,1"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("bit-identical across thread counts: yes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("speedup"), std::string::npos) << r.out;

  std::istringstream csv(test::slurp(dir + "/bench.csv"));
  std::string header;
  ASSERT_TRUE(std::getline(csv, header));
  const auto columns = split(header, ',');
  // The columns before the thread sweep's keep their places.
  ASSERT_GE(columns.size(), 25u);
  EXPECT_EQ(columns[0], "n_seg");
  EXPECT_EQ(columns[6], "median_ms");
  EXPECT_EQ(columns[21], "full_newton_per_step");
  auto col = [&](const std::string& name) {
    const auto at = std::find(columns.begin(), columns.end(), name) - columns.begin();
    EXPECT_LT(at, static_cast<long>(columns.size())) << "no column " << name;
    return static_cast<std::size_t>(at);
  };
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(csv, line);) rows.push_back(split(line, ','));
  ASSERT_EQ(rows.size(), 4u);
  const int n_seg[4] = {4, 4, 48, 48}, threads[4] = {1, 2, 1, 2};  // counts sorted ascending
  for (int k = 0; k < 4; ++k) {
    const auto& row = rows[k];
    ASSERT_EQ(row.size(), columns.size());
    EXPECT_EQ(std::stoi(row[col("n_seg")]), n_seg[k]);
    EXPECT_EQ(std::stoi(row[col("threads")]), threads[k]);
    EXPECT_EQ(std::stoi(row[col("steps")]), 4);
    // The slowest step: no faster than the median or the mean, and one of the 4 steps.
    const double max_ms = std::stod(row[col("max_ms")]);
    EXPECT_GE(max_ms, std::stod(row[col("median_ms")]) * (1 - 1e-5));
    EXPECT_GE(max_ms, std::stod(row[col("mean_ms")]) * (1 - 1e-5));
    EXPECT_GE(std::stoi(row[col("max_step")]), 1);
    EXPECT_LE(std::stoi(row[col("max_step")]), 4);
    const double speedup = std::stod(row[col("speedup")]);
    const double efficiency = std::stod(row[col("efficiency")]);
    if (threads[k] == 1) {
      EXPECT_EQ(speedup, 1.0);
      EXPECT_EQ(efficiency, 1.0);
    } else {
      // Against the 1-thread row of the same size, from the medians as written (5 and 6
      // significant digits).
      const double expected =
          std::stod(rows[k - 1][col("median_ms")]) / std::stod(row[col("median_ms")]);
      EXPECT_NEAR(speedup, expected, 1e-4 * expected);
      EXPECT_NEAR(efficiency, speedup / 2.0, 1e-4 * speedup);
    }
  }
  const std::string png = test::slurp(dir + "/bench.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  std::filesystem::remove_all(dir);
}

// With several counts the runs take turns of a few steps (a drift in the machine's speed
// then slows every count alike), still bit-identical; a step that fails is tried at every
// count, where it fails alike: each count keeps its row, failed at that same step.
TEST(BenchCommand, ThreadCountsTakeTurnsAndAFailedStepFailsAtEveryCount) {
  const std::string dir = ::testing::TempDir() + "/bench_turns_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  // Two Newton iterations per step at most: the squash's first harder step fails.
  const test::ProcessResult r =
      test::run_invfree({"bench", "--sizes", "8", "--steps", "50", "--out", dir, "--threads", "1,2",
                         "--set", "time.max_newton=2"});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("failed"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("take turns of 10 steps"), std::string::npos) << r.out;
  std::istringstream csv(test::slurp(dir + "/bench.csv"));
  std::string header;
  ASSERT_TRUE(std::getline(csv, header));
  const auto columns = split(header, ',');
  const auto at = [&](const char* name) {
    return static_cast<std::size_t>(std::find(columns.begin(), columns.end(), name) -
                                    columns.begin());
  };
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(csv, line);) rows.push_back(split(line, ','));
  ASSERT_EQ(rows.size(), 2u) << "one row per count, the second too";
  const int steps = std::stoi(rows[0][at("steps")]);
  EXPECT_GT(steps, 0);
  EXPECT_LT(steps, 50);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(std::stoi(rows[k][at("threads")]), k + 1);
    EXPECT_EQ(std::stoi(rows[k][at("steps")]), steps);
    EXPECT_NE(rows[k][at("solver")].find("(failed at step " + std::to_string(steps + 1) + ")"),
              std::string::npos)
        << rows[k][at("solver")];
  }
  // The paired speed-up (the median of the turns' time ratios): 1 for the smallest count,
  // a positive ratio for the other (the 3 turns complete before the failure).
  ASSERT_LT(at("paired_speedup"), columns.size());
  EXPECT_EQ(std::stod(rows[0][at("paired_speedup")]), 1.0);
  const double paired = std::stod(rows[1][at("paired_speedup")]);
  EXPECT_GT(paired, 0.0);
  EXPECT_TRUE(std::isfinite(paired));
  std::filesystem::remove_all(dir);
}

// One count works as before: one row per size at that count, speed-up and efficiency 1,
// and no comparison across counts.
TEST(BenchCommand, OneThreadCountIsOneRowPerSize) {
  const std::string dir = ::testing::TempDir() + "/bench_one_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  const test::ProcessResult r = test::run_invfree(
      {"bench", "--sizes", "4,6", "--steps", "3", "--out", dir, "--threads", "2"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.find("bit-identical"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("speedup"), std::string::npos) << "today's table: " << r.out;
  std::vector<std::vector<std::string>> rows;
  std::istringstream csv(test::slurp(dir + "/bench.csv"));
  for (std::string line; std::getline(csv, line);) rows.push_back(split(line, ','));
  ASSERT_EQ(rows.size(), 3u);
  const auto& header = rows[0];
  const auto at = [&](const char* name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) -
                                    header.begin());
  };
  ASSERT_LT(at("efficiency"), header.size());
  for (std::size_t k = 1; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), header.size());
    EXPECT_EQ(rows[k][at("threads")], "2");
    EXPECT_EQ(rows[k][at("speedup")], "1");
    EXPECT_EQ(rows[k][at("efficiency")], "1");
  }
  std::filesystem::remove_all(dir);
}

// Bad lists stop before anything runs or is written: one line naming --threads, exit 2.
TEST(BenchCommand, BadThreadListsAreBadInput) {
  const std::string dir = ::testing::TempDir() + "/bench_bad_threads_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  for (const char* threads : {"0", "-2", "x", "1,x", "1.5", "1,,2", "1,", "", "257", "1,2,1", "2,2"}) {
    const test::ProcessResult r = test::run_invfree(
        {"bench", "--sizes", "4", "--steps", "2", "--out", dir, "--threads", threads});
    EXPECT_EQ(r.code, 2) << "--threads \"" << threads << "\": " << r.out;
    EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/bench.csv")) << threads;
  }
  const test::ProcessResult twice = test::run_invfree(
      {"bench", "--sizes", "4", "--steps", "2", "--out", dir, "--threads", "1,2,1"});
  EXPECT_NE(twice.err.find("1 is listed twice"), std::string::npos) << twice.err;
  std::filesystem::remove_all(dir);
}

// A reduced scene ([reduced]) is timed against its full model on each mesh: the last two
// columns hold the full model's median ms and Newton iterations per step, empty for a
// scene without a basis (the test above).
TEST(BenchCommand, AReducedSceneRunsItsFullModelToo) {
  const std::string dir = ::testing::TempDir() + "/bench_reduced_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  const test::ProcessResult r = test::run_invfree(
      {"bench", "--scene", "course-9-affine", "--sizes", "4,6", "--steps", "40", "--out", dir});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("x faster reduced"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("dense-ldlt-r6"), std::string::npos) << r.out;
  std::vector<std::vector<std::string>> rows;
  std::istringstream csv(test::slurp(dir + "/bench.csv"));
  for (std::string line; std::getline(csv, line);) rows.push_back(split(line, ','));
  ASSERT_EQ(rows.size(), 3u);
  const auto& header = rows[0];
  const auto full = std::find(header.begin(), header.end(), "full_median_ms") - header.begin();
  const auto newton = std::find(header.begin(), header.end(), "full_newton_per_step") - header.begin();
  ASSERT_LT(full, static_cast<long>(header.size()));
  ASSERT_LT(newton, static_cast<long>(header.size()));
  for (size_t k = 1; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), header.size());
    EXPECT_GT(std::stod(rows[k][full]), 0.0);
    EXPECT_GE(std::stod(rows[k][newton]), 1.0);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace invfree
