// Determinism: the same scene and build give bit-identical positions across runs, across
// processes and across thread counts (INVFREE_THREADS), and a stored run's final state
// still hashes to the value recorded in tests/reliability/stored_run.txt.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "scene/scene.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "simulation.h"
#include "tests/reliability/process.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

std::uint64_t fnv1a64(const double* values, size_t count) {
  std::uint64_t h = 0xCBF29CE484222325ull;
  const auto* bytes = reinterpret_cast<const unsigned char*>(values);  // x86-64: little-endian
  for (size_t i = 0; i < count * sizeof(double); ++i) h = (h ^ bytes[i]) * 0x100000001B3ull;
  return h;
}

std::string hex(std::uint64_t h) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(h));
  return buf;
}

Simulation run(const SceneDef& scene, int steps) {
  Simulation sim = make_simulation(scene);
  for (int k = 0; k < steps; ++k) {
    const StepReport r = step(sim);
    EXPECT_EQ(r.status, StepStatus::Ok) << scene.name << " step " << k << ": " << r.message;
    if (r.status != StepStatus::Ok) break;
  }
  return sim;
}

bool bit_identical(const VecX& a, const VecX& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

std::vector<SceneDef> scenes_under_test() {
  std::vector<SceneDef> out = {*load_builtin_scene("compress").scene,
                               *load_builtin_scene("drop").scene};
  SceneDef jittered =
      *load_builtin_scene("compress").scene;  // irregular mesh, another model and projection
  EXPECT_EQ(apply_override(jittered, "mesh.n_seg=12"), "");
  EXPECT_EQ(apply_override(jittered, "mesh.jitter=0.2"), "");
  EXPECT_EQ(apply_override(jittered, "material.model=stable-neo-hookean"), "");
  EXPECT_EQ(apply_override(jittered, "solver.projection=full"), "");
  jittered.name = "jittered";
  out.push_back(jittered);
  return out;
}

TEST(Determinism, RunsInOneProcessAreBitIdentical) {
  for (const SceneDef& scene : scenes_under_test()) {
    const Simulation a = run(scene, 200), b = run(scene, 200);
    EXPECT_TRUE(bit_identical(a.x, b.x)) << scene.name;
    EXPECT_TRUE(bit_identical(a.v, b.v)) << scene.name;
    EXPECT_EQ(std::memcmp(&a.ceiling_y, &b.ceiling_y, sizeof(double)), 0) << scene.name;
    EXPECT_EQ(a.step_count, 200) << scene.name;
  }
}

// The last OBJ of a CLI run (17 significant digits, so the text is the exact doubles)
// and the CSV without its wall-clock column.
struct CliRun {
  std::string obj, csv;
};

CliRun run_cli(const std::string& dir, const std::vector<std::string>& extra_args, int threads,
               int steps) {
  std::filesystem::remove_all(dir);
  std::vector<std::string> args = {"simulate",   "--steps", std::to_string(steps), "--obj",
                                   dir + "/obj", "--csv",   dir + "/run.csv"};
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  const test::ProcessResult r =
      test::run_invfree(args, {"INVFREE_THREADS=" + std::to_string(threads)});
  EXPECT_EQ(r.code, 0) << r.err;
  CliRun out;
  out.obj = test::slurp(dir + "/obj/" + std::to_string(steps) + ".obj");
  std::istringstream csv(test::slurp(dir + "/run.csv"));
  for (std::string line; std::getline(csv, line);)
    out.csv += line.substr(0, line.rfind(',')) + "\n";
  std::filesystem::remove_all(dir);
  return out;
}

TEST(Determinism, ProcessesAndThreadCountsAgreeBitForBit) {
  const std::string base = ::testing::TempDir() + "/determinism_" + std::to_string(::getpid());
  const std::vector<std::vector<std::string>> variants = {
      {"--scene", "compress"},
      {"--scene", "compress", "--set", "mesh.n_seg=24", "--set", "mesh.jitter=0.2"},
  };
  for (const auto& v : variants) {
    const CliRun one = run_cli(base + "_1", v, 1, 150);
    ASSERT_FALSE(one.obj.empty());
    ASSERT_GT(one.csv.size(), 150u * 20u);
    for (int threads : {1, 2, 3}) {
      const CliRun other = run_cli(base + "_" + std::to_string(threads) + "b", v, threads, 150);
      EXPECT_EQ(other.obj, one.obj)
          << "positions differ with " << threads << " threads: " << v.back();
      EXPECT_EQ(other.csv, one.csv)
          << "per-step table differs with " << threads << " threads: " << v.back();
    }
  }
}

// Every linear solver backend (the scene key solver.linear_solver) claims bit-identical
// results for any INVFREE_THREADS. n_seg 48 is large enough for CHOLMOD's supernodal
// factorisation to call multithreaded BLAS, whose rounding would otherwise depend on the
// thread count (three different trajectories from step 1 for 1, 2 and 3 threads).
TEST(Determinism, EveryLinearSolverAgreesAcrossThreadCounts) {
  const std::string base =
      ::testing::TempDir() + "/determinism_solver_" + std::to_string(::getpid());
  for (const char* solver : {"auto", "ldlt", "cholmod", "pcg"}) {
    const std::vector<std::string> v = {"--set", "mesh.n_seg=48", "--set",
                                        std::string("solver.linear_solver=") + solver};
    const CliRun one = run_cli(base + "_1", v, 1, 10);
    ASSERT_FALSE(one.obj.empty()) << solver;
    for (int threads : {2, 3}) {
      const CliRun other = run_cli(base + "_" + std::to_string(threads), v, threads, 10);
      EXPECT_EQ(other.obj, one.obj)
          << solver << ": positions differ with " << threads << " threads";
      EXPECT_EQ(other.csv, one.csv)
          << solver << ": per-step table differs with " << threads << " threads";
    }
  }
}

TEST(Determinism, StoredRunHash) {
  const std::string path = std::string(::invfree::test::source_dir()) + "/tests/reliability/stored_run.txt";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::string scene_name, expected;
  int steps = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string key, value;
    words >> key >> value;
    if (key == "scene") scene_name = value;
    if (key == "steps") steps = std::stoi(value);
    if (key == "positions_fnv1a64") expected = value;
  }
  ASSERT_FALSE(scene_name.empty());
  ASSERT_GT(steps, 0);
  const SceneLoad scene = load_scene(scene_name);
  ASSERT_TRUE(scene.scene) << scene.error;
  const Simulation sim = run(*scene.scene, steps);
  ASSERT_EQ(sim.step_count, steps);
  const std::string actual = hex(fnv1a64(sim.x.data(), sim.x.size()));
  EXPECT_EQ(actual, expected) << "final positions of '" << scene_name << "' after " << steps
                              << " steps hash to " << actual << ", stored " << expected
                              << ". If the numerics changed on purpose, see " << path
                              << " to regenerate.";
}

}  // namespace
}  // namespace invfree
