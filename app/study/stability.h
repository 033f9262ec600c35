// `invfree stability`: every method (methods.h) on every stress scene (stress_scenes.h),
// each run classified (verdict.h) with the step of failure and the wall time, and the
// final or failing frame kept for the contact sheet (contact_sheet.h).
// Symplectic Euler takes 20 steps per scene step (it is explicit: "tiny steps"); every
// other method runs at the scene's own h.
#pragma once

#include <string>
#include <vector>

#include "app/study/run.h"
#include "app/study/sweep_options.h"

namespace invfree {

struct StabilityCell {
  std::string method, scene;
  Verdict verdict = Verdict::Ok;
  long fail_step = -1;
  double wall_s = 0.0;  // wall-clock seconds inside step() for the whole run
  double h = 0.0;       // the step the method actually used
  int substeps = 1;     // steps per scene step (symplectic Euler: 20)
  long steps = 0;
  double duration = 0.0;
  std::string message;
  Frame frame;
};

struct StabilityResult {
  std::vector<std::string> methods, method_labels;  // rows
  std::vector<std::string> scenes, scene_labels;    // columns
  std::vector<StabilityCell> cells;                 // row-major
  std::vector<std::string> scene_errors;            // a stress file that failed to load
  double total_wall_s = 0.0;
  bool quick = false;    // each scene only until its defining event (--quick)
  bool stopped = false;  // `stop` returned true: the result is incomplete
  const StabilityCell& at(size_t method, size_t scene) const {
    return cells[method * scenes.size() + scene];
  }
};

// quick: each scene until its defining event only (quick_stability_duration), not the
// time to settle after it.
StabilityResult run_stability(const SweepOptions& options);

// When a failed run failed, for people: "t = 0.62 s, step 62", or for a method taking
// substeps "t = 0.617 s, substep 1,234 of h/20".
std::string failure_time(const StabilityCell& cell);

std::string stability_csv(const StabilityResult& r);
std::string stability_markdown(const StabilityResult& r);

}  // namespace invfree
