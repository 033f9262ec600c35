// `invfree study`: speed against accuracy for every method (methods.h) on one scene.
// For each method the time step h is swept (implicit methods around the scene's h,
// symplectic Euler at 1/10 of it and below, where it can be stable); for every implicit
// method the Newton tolerance is swept at the scene's h; for the lecture's method the mesh
// resolution is swept too. Accuracy: RMS node-position error over the nodes and the
// sample times, relative to the side length, against a converged reference of the same
// scene and model (lecture's solver, h / 1600 (quick: / 100), tol / 1e4; computed here).
// Speed: wall-clock seconds inside step() per simulated second.
// Inputs: a validated scene and options. Output: the rows of study.csv and the fitted
// convergence slope; charts are drawn by study_chart.h.
#pragma once

#include <string>
#include <vector>

#include "app/study/sweep_options.h"
#include "scene/scene.h"

namespace invfree {

struct StudyRow {
  std::string method;
  double h = 0.0, tol = 0.0;
  int n_seg = 0;
  double wall_s = 0.0;        // wall-clock seconds per simulated second (over the part that ran)
  double error = 0.0;         // NaN when the run failed or has no reference
  double newton_iters = 0.0;  // mean Newton iterations per step
  std::string failure;        // verdict: "ok", "penetrated", ... (verdict.h)
  long fail_step = -1;
  std::string message;
};

// Whether a material model's errors fall with h: the fitted slope of log(error) against
// log(h) over every ok point of the model's methods in the h sweep. Below
// kMinConvergenceSlope, or with no error below kMaxConvergedError of the side, the errors
// measure how far runs drift from the reference (contact events out of phase, bodies on
// other paths), not how accurately a method solves: study.png draws no Pareto front for the
// model and says why, and `invfree study` warns. Fewer than 3 points are not judged.
struct ModelConvergence {
  std::string model;  // method_model(): "neo-hookean", "linear", ...
  double slope = 0.0;
  int points = 0;
  double error_lo = 0.0, error_hi = 0.0;  // the range of its errors
  bool judged = false;                    // at least 3 points to fit
  bool converges = false;  // judged, slope >= kMinConvergenceSlope, error_lo <= kMaxConvergedError
};
constexpr double kMinConvergenceSlope = 0.1;
constexpr double kMaxConvergedError = 0.2;

struct StudyResult {
  SceneDef scene;                    // the scene as given (before any method's settings)
  std::vector<std::string> methods;  // the study methods that ran (--methods), in table order
  std::vector<double> sample_times;
  double duration = 0.0;
  double reference_h = 0.0, reference_tol = 0.0;
  int mesh_reference_n_seg = 0;
  double mesh_reference_h = 0.0;
  std::vector<StudyRow> rows;
  std::vector<std::string> reference_failures;  // one line each, empty when all converged
  double lecture_slope = 0.0;                   // fitted d log(error) / d log(h), lecture's method
  // The classic check: the lecture's method on the same scene with contact switched off
  // (rows "lecture-no-contact"), where the motion is smooth and implicit Euler's first
  // order shows at every h swept; with stiff contact it only shows for h far below the
  // contact time scale (the notes of study.png say why).
  double smooth_slope = 0.0;
  double lecture_slope_small_h = 0.0;  // the fit over the four smallest h of the scene itself
  std::vector<ModelConvergence> convergence;  // one per model that ran
  double total_wall_s = 0.0;
  bool stopped = false;  // `stop` returned true: the result is incomplete
};

// Errors in the scene (e.g. a method cannot be applied) are reported in rows; never throws.
// quick: fewer h, tolerances and meshes, and a coarser reference (h / 100), over the same
// simulated time as the full study, so every verdict it prints is the full study's (the
// squeeze that decides them is inside both).
StudyResult run_study(const SceneDef& scene, const SweepOptions& options);

// The times at which the study compares runs with their reference; the last is how long
// every run lasts. The same for the quick and the full study.
std::vector<double> study_sample_times(const SceneDef& scene, bool quick);

// Whether `method` is one of the study's (result.methods; an empty list: every method).
bool study_ran_method(const StudyResult& result, const std::string& method);
// The study methods that ran, in table order.
std::vector<std::string> study_methods_run(const StudyResult& result);

// The convergence of `model` (null when the model did not run).
const ModelConvergence* model_convergence(const StudyResult& result, const std::string& model);
// The models judged whose errors do not fall with h (in the order they ran).
std::vector<const ModelConvergence*> non_converging_models(const StudyResult& result);

std::string study_csv(const StudyResult& result);

// No run of the scene's sweeps ended ok (the n/a rows, which never ran, aside; a study
// with no run at all too): study.png's panels say so in their titles, and `invfree study`
// exits 3.
bool every_run_failed(const StudyResult& result);

// Which sweep a row belongs to (a row can be in several: the base point is in all).
bool in_h_sweep(const StudyResult& r, const StudyRow& row);
bool in_tol_sweep(const StudyResult& r, const StudyRow& row);
bool in_mesh_sweep(const StudyResult& r, const StudyRow& row);

}  // namespace invfree
