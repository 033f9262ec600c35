// How sensitive a stretch of a run is to rounding: runs `compress` (self-contact switched
// off: the loops of docs/performance.md's fold section) at n_seg to step
// `from`, keeps the state (positions, velocities, ceiling, its penalty stiffness), and
// restarts from it once as it is and once per perturbation size eps (every coordinate
// moved by at most eps / 2, a fixed pseudo-random pattern), each time up to step `to`,
// printing the Newton iterations (total and worst step) and the mean ms per step.
// Every restart begins with a fresh factorisation, so even the unperturbed one is a draw
// of its own. For n_seg 256's fold steps (near step 250, where Newton takes the most
// iterations: `invfree bench --sizes 256` reports the worst step):
//   build/release/tests/bench/invfree_fold_restarts 256 225 265 1e-12 2e-12 3e-12
// Not a test: it takes minutes at n_seg 256 and asserts nothing.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"

using namespace invfree;

namespace {

struct SavedState {
  VecX x, v;
  double ceiling_y = 0.0, ceiling_nominal = 0.0, time = 0.0, ceiling_stiffness = 0.0;
  long step_count = 0;
};

SavedState save(const Simulation& sim) {
  SavedState s;
  s.x = sim.x;
  s.v = sim.v;
  s.ceiling_y = sim.ceiling_y;
  s.ceiling_nominal = sim.ceiling_nominal;
  s.time = sim.time;
  s.ceiling_stiffness = sim.ceiling_stiffness;
  s.step_count = sim.step_count;
  return s;
}

void restore(const SavedState& s, Simulation& sim) {
  sim.x = s.x;
  sim.v = s.v;
  sim.ceiling_y = s.ceiling_y;
  sim.ceiling_nominal = s.ceiling_nominal;
  sim.time = s.time;
  sim.ceiling_stiffness = s.ceiling_stiffness;
  sim.step_count = s.step_count;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s N_SEG FROM_STEP TO_STEP [EPS ...]\n", argv[0]);
    return 2;
  }
  const int n_seg = std::atoi(argv[1]);
  const long from = std::atol(argv[2]), to = std::atol(argv[3]);
  if (n_seg < 1 || from < 0 || to <= from) {
    std::fprintf(stderr, "need N_SEG >= 1 and 0 <= FROM_STEP < TO_STEP\n");
    return 2;
  }
  std::vector<double> eps{0.0};
  for (int i = 4; i < argc; ++i) eps.push_back(std::atof(argv[i]));

  SceneDef scene = *load_builtin_scene("compress").scene;
  scene.n_seg = n_seg;
  scene.has_self_contact = false;  // the loops it studies form only without self-contact
  if (const std::string error = validate_scene(scene); !error.empty()) {
    std::fprintf(stderr, "n_seg %d: %s\n", n_seg, error.c_str());
    return 2;
  }
  Simulation sim = make_simulation(scene);
  while (sim.step_count < from) {
    const StepReport r = step(sim);
    if (r.status != StepStatus::Ok) {
      std::fprintf(stderr, "step %ld failed before the restart point: %s\n", sim.step_count + 1,
                   r.message.c_str());
      return 3;
    }
  }
  const SavedState saved = save(sim);

  for (double e : eps) {
    Simulation run = make_simulation(scene);
    restore(saved, run);
    unsigned seed = 12345u;
    for (Eigen::Index i = 0; i < run.x.size(); ++i) {
      seed = seed * 1103515245u + 12345u;
      run.x[i] += e * (((seed >> 8) & 0xffff) / 65536.0 - 0.5);
    }
    int total = 0, worst = 0;
    long worst_step = 0;
    double ms = 0.0;
    std::string outcome = "ok";
    while (run.step_count < to) {
      const StepReport r = step(run);
      if (r.status != StepStatus::Ok) {
        outcome = "step " + std::to_string(run.step_count + 1) + " failed: " + r.message;
        break;
      }
      total += r.newton_iterations;
      ms += r.wall_ms;
      if (r.newton_iterations > worst) {
        worst = r.newton_iterations;
        worst_step = run.step_count;
      }
    }
    const long steps = std::max(1L, run.step_count - from);
    std::printf(
        "eps %-8.1e steps %ld-%ld: Newton %d in all, worst %d (step %ld), %.1f ms/step, %s\n", e,
        from + 1, run.step_count, total, worst, worst_step, ms / steps, outcome.c_str());
    std::fflush(stdout);
  }
  return 0;
}
