// `invfree stability`: every method (methods.h) on every stress scene (stress_scenes.h),
// each run classified (verdict.h) with the step of failure and the wall time, and the
// final or failing frame kept for the contact sheet (contact_sheet.h).
// Symplectic Euler takes 20 steps per scene step (it is explicit: "tiny steps"); every
// other method runs at the scene's own h.
#pragma once

#include <span>
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
  double min_det_f = NAN;  // the smallest det F over the run (up to where it ended)
  Frame frame;
};

// How a cell reads: ok, a failure, an inversion its model allows (neutral, not red), n/a.
enum class CellClass { Ok, Failed, InversionAllowed, NotApplicable };
CellClass cell_class(Verdict v);

// The course's chapter 0 (issue 29): its explicit integrator (symplectic Euler, the scene's
// own) on the hanging mass-spring square, at the demo's h and at a larger one. An explicit
// step is stable only while omega_max h <= 2; the square's highest rest frequency is
// omega_max = 83.3 rad/s (h <= 0.024 s), so h = 0.01 s is ok (omega_max h = 0.83) and
// h = 0.03 s (2.5) blows up. Rows of their own after the table (not a method on the
// stress scenes: the row is about h, not about a scene).
struct ExplicitRow {
  const char* scene;
  double h;
  double omega_h;  // omega_max h at rest, for the table
};
std::span<const ExplicitRow> explicit_rows();
// The CSV's method name of an explicit row: "chapter-0-explicit-h0.03".
std::string explicit_row_method(const ExplicitRow& row);
// Runs one explicit row as run_stability does (quick: quick_stability_duration).
StabilityCell run_explicit_row(const ExplicitRow& row, bool quick);

struct StabilityResult {
  std::vector<std::string> methods, method_labels;  // rows
  std::vector<std::string> scenes, scene_labels;    // columns
  std::vector<StabilityCell> cells;                 // row-major
  std::vector<StabilityCell> explicit_cells;        // explicit_rows(), in order
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
// options.methods picks the rows (empty: every method of stability_methods()),
// options.scenes the columns (empty: every stress scene, stress_scenes()).
StabilityResult run_stability(const SweepOptions& options);

// When a failed run failed, for people: "t = 0.62 s, step 62", or for a method taking
// substeps "t = 0.617 s, substep 1,234 of h/20".
std::string failure_time(const StabilityCell& cell);

std::string stability_csv(const StabilityResult& r);
std::string stability_markdown(const StabilityResult& r);

}  // namespace invfree
