// Soak: `compress` for 10,000 steps while a fixed pseudo-random script changes mu,
// lambda, h and the ceiling's motion every 50 steps (through update_scene, as the live
// sliders do). At every step it checks, independently of the library's own checker:
// the step succeeded, every value is finite, det F > 0 in every triangle (neo-Hookean),
// every node strictly between ground and ceiling, and the incremental potential at the
// accepted state is not above its value at the step's start. Memory must stay flat.
#include <gtest/gtest.h>
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include "potential/incremental_potential.h"
#include "scene/scene.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"
#include "solver/step_workspace.h"

namespace invfree {
namespace {

// SplitMix64: a fixed script, identical on every platform and run.
struct Script {
  std::uint64_t state;
  double uniform(double lo, double hi) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return lo + (hi - lo) * (static_cast<double>(z >> 11) * 0x1.0p-53);
  }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
};

// The next settings: mu from 3e3 to 2e5 Pa, lambda from 0 to 30 mu (nu up to ~0.48), h
// from 2 to 20 ms, and a new ceiling height between 0.22 m above the ground (the square
// squashed to a fifth of its height) and y = 0.7 (free), reached at up to 1 m/s within
// the next 50 steps. Newton keeps the scene's cap (100 iterations): every step must
// converge under it.
SceneDef next_settings(const SceneDef& current, double ceiling_nominal, int steps, Script& script) {
  SceneDef s = current;
  s.lame.mu = script.log_uniform(3e3, 2e5);
  s.lame.lambda = script.uniform(0.0, 1.0) < 0.1 ? 0.0 : s.lame.mu * script.log_uniform(1e-2, 30.0);
  s.h = script.log_uniform(0.002, 0.02);
  const double target = script.uniform(s.ground_y + 0.22, 0.7);
  s.ceiling_velocity = std::clamp((target - ceiling_nominal) / (steps * s.h), -1.0, 1.0);
  // The ceiling moves while its height is above `stop`: down to the target, or up freely.
  s.ceiling_stop = target < ceiling_nominal ? target : s.ground_y + 0.2;
  return s;
}

long resident_kib() {
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return resident * (::sysconf(_SC_PAGESIZE) / 1024);
}

// Independent invariant check; returns "" or what is broken.
std::string broken_invariant(const Simulation& sim) {
  if (!sim.x.allFinite() || !sim.v.allFinite() || !std::isfinite(sim.ceiling_y) ||
      !std::isfinite(sim.time))
    return "non-finite state";
  for (int t = 0; t < sim.mesh.triangle_count(); ++t) {
    const auto& tri = sim.mesh.triangles[t];
    const Vec2 a = sim.x.segment<2>(2 * tri[1]) - sim.x.segment<2>(2 * tri[0]);
    const Vec2 b = sim.x.segment<2>(2 * tri[2]) - sim.x.segment<2>(2 * tri[0]);
    if (!(a.x() * b.y() - a.y() * b.x() > 0.0))
      return "triangle " + std::to_string(t) + " has det F <= 0";
  }
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    const double y = sim.x[2 * i + 1];
    if (!(y > sim.scene.ground_y)) return "node " + std::to_string(i) + " on or through the ground";
    if (!(y < sim.ceiling_y)) return "node " + std::to_string(i) + " on or through the ceiling";
  }
  return "";
}

TEST(Soak, TenThousandStepsWithChangingParameters) {
  constexpr int kSteps = 10000, kEvery = 50;
  Simulation sim = make_simulation(*load_builtin_scene("compress").scene);
  ASSERT_EQ(sim.scene.model, Model::NeoHookean);
  Script script{20240607};
  long violations = 0, changes = 0, newton_iterations = 0;
  int max_iterations = 0;
  std::string first_violation;
  auto violation = [&](const std::string& what) {
    if (violations++ == 0) first_violation = "step " + std::to_string(sim.step_count) + ": " + what;
  };
  double lowest_ceiling = sim.ceiling_y, highest_after_press = -1e300;
  long rss_warm = 0;
  size_t heap_warm = 0;
  VecX z_start;
  for (int k = 0; k < kSteps; ++k) {
    if (k > 0 && k % kEvery == 0) {
      const SceneDef next = next_settings(sim.scene, sim.ceiling_nominal, kEvery, script);
      ASSERT_EQ(validate_scene(next), "") << "the script must only make valid scenes";
      update_scene(sim, next);
      ++changes;
    }
    if (k == 1000) {  // after the first changes: every buffer has its size
      rss_warm = resident_kib();
      heap_warm = mallinfo2().uordblks;
    }
    // The step's start [x; c], to evaluate the potential there under the step's final
    // problem (the ceiling penalty may have stiffened during the step).
    const int n = sim.mesh.node_count();
    z_start.resize(2 * n + 1);
    z_start.head(2 * n) = sim.x;
    z_start[2 * n] = sim.ceiling_y;
    const long before = sim.step_count;
    const StepReport r = step(sim);
    if (r.status != StepStatus::Ok) {
      violation(std::string("step failed: ") + step_status_name(r.status) + ": " + r.message);
      continue;
    }
    if (sim.step_count != before + 1) violation("step count did not advance");
    newton_iterations += r.newton_iterations;
    max_iterations = std::max(max_iterations, r.newton_iterations);
    if (auto e = broken_invariant(sim); !e.empty()) violation(e);
    // Energy decrease within the step. Newton's line search accepts only non-increasing
    // potentials, except that near convergence it takes the filtered step when the
    // predicted decrease is below E's own rounding noise, 64 eps (|E| + 1) per iteration
    // (core/newton.cpp); that noise is the only slack allowed.
    const double e_start = ip_energy(sim.workspace->problem, sim.workspace->caches, z_start);
    const double noise = 64.0 * std::numeric_limits<double>::epsilon() * (std::abs(e_start) + 1.0) *
                         std::max(1, r.newton_iterations);
    if (!std::isfinite(r.energy) || !std::isfinite(e_start))
      violation("non-finite incremental potential");
    if (!(r.energy <= e_start + noise))
      violation("incremental potential rose within the step: " + std::to_string(e_start) + " -> " +
                std::to_string(r.energy));
    lowest_ceiling = std::min(lowest_ceiling, sim.ceiling_y);
    if (lowest_ceiling < 0.0) highest_after_press = std::max(highest_after_press, sim.ceiling_y);
  }
  const long rss_end = resident_kib();
  const size_t heap_end = mallinfo2().uordblks;
  std::printf(
      "soak: %d steps, %ld parameter changes, %ld invariant violations, %.2f Newton "
      "iterations/step (max %d), "
      "ceiling down to %.3f and up again to %.3f, RSS %ld -> %ld KiB, heap in use %zu -> %zu "
      "bytes\n",
      kSteps, changes, violations, double(newton_iterations) / kSteps, max_iterations,
      lowest_ceiling, highest_after_press, rss_warm, rss_end, heap_warm, heap_end);
  EXPECT_EQ(violations, 0) << "first: " << first_violation;
  EXPECT_EQ(sim.step_count, kSteps);
  EXPECT_EQ(changes, kSteps / kEvery - 1);
  // The script really exercised the ceiling: pressed the square hard and let it go again.
  EXPECT_LT(lowest_ceiling, -0.6);
  EXPECT_GT(highest_after_press, 0.3);
  // Flat memory: nothing grows with the number of steps. Heap bytes in use are exact
  // (0 under AddressSanitizer, whose allocator glibc does not see; LeakSanitizer covers
  // that build); resident memory may move by a few pages of allocator slack.
  EXPECT_LE(heap_end, heap_warm + 16 * 1024) << "heap grew by " << heap_end - heap_warm << " bytes";
  EXPECT_LE(rss_end, rss_warm + 1024) << "resident memory grew by " << rss_end - rss_warm << " KiB";
}

}  // namespace
}  // namespace invfree
