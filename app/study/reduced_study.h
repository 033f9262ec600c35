// `invfree study`'s chart of the course's chapter 9: speed against accuracy of reduced
// bases. The chapter's scene (the neo-Hookean square dropped on the ground,
// assets/scenes/course-9-*.toml) is run with the full model ([reduced] basis = "full") and
// with every reduced model -- polynomial bases of order 1 (affine), 2 and 3, and modal bases
// of several sizes -- over the same steps, each at the scene's own settings (h, tol,
// max_newton). Speed: the median of StepReport::wall_ms over the run (ms per step). Error:
// the largest distance of any node from its position in the full model at the same step,
// over the whole run (m); the full model's is 0 by definition.
// A modal count that splits a degenerate pair of eigenvalues is refused by the scene checks
// (scene/reduced_basis.h); the study rounds it up to the next count that splits none.
// Inputs: the sweep's options (quick: fewer steps, models and meshes). Outputs: rows, their
// CSV and a panel of study.png.
#pragma once

#include <string>
#include <vector>

#include "app/plot/chart.h"
#include "app/study/sweep_options.h"

namespace invfree {

struct ReducedStudyRow {
  std::string basis;       // "full", "polynomial" or "modal" ([reduced] basis)
  int order_or_modes = 0;  // the polynomial order or the modal count; 0 for the full model
  int unknowns = 0;        // the subspace's dimension r (the full model: 2 x nodes)
  int n_seg = 0;
  double ms_per_step = 0.0;      // median of the steps' wall_ms
  double max_error_m = 0.0;      // 0 for the full model; NaN when the run failed
  double newton_per_step = 0.0;  // mean Newton iterations per step
  std::string failure;           // "ok", or the failing step's status and step
};

struct ReducedStudy {
  std::string scene;                  // the built-in scene run ("course-9-affine")
  long steps = 0;                     // steps per run
  std::vector<ReducedStudyRow> rows;  // per mesh: the full model first, then the reduced ones
  bool stopped = false;
};

ReducedStudy run_reduced_study(const SweepOptions& options);

// "affine (6)", "quadratic (12)", "cubic (20)", "modal 12", "full (242)".
std::string reduced_model_label(const ReducedStudyRow& row);

// basis,order_or_modes,unknowns,n_seg,ms_per_step,max_error_m,newton_per_step,failure
// (max_error_m empty when the run failed).
std::string reduced_study_csv(const ReducedStudy& study);

// Error (m) against ms per step, log-log: per mesh, one series of the polynomial bases and
// one of the modal bases (each point labelled), and the full model's ms per step as a
// dashed vertical line.
ChartSpec reduced_study_panel(const ReducedStudy& study);

}  // namespace invfree
