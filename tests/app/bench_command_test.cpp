// `invfree bench`: writes a CSV row per size with consistent columns and a PNG chart,
// reports the speed-up against the reference demo, and rejects bad sizes with one line.
#include <gtest/gtest.h>

#include <algorithm>
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
