// One run of a scene for the study and the stability sweep: steps for `duration`
// simulated seconds, records the node positions at the sample times, classifies how it
// ended (verdict.h) and keeps the final or failing frame for the contact sheet.
// Inputs: a scene (validated here: a scene the method cannot start is n/a) and options.
// Output: a RunResult; never throws, never loops forever (each step is bounded by the
// scene's max_newton).
#pragma once

#include <string>
#include <vector>

#include "app/study/verdict.h"
#include "simulation.h"

namespace invfree {

struct Frame {
  Mesh mesh;  // rest data unused; triangles index `x`
  VecX x;
  std::vector<double> det_f;
  bool has_ground = false, has_ceiling = false;
  double ground_y = 0.0, ceiling_y = 0.0, side = 1.0;
  double time = 0.0;
};

struct RunOptions {
  double duration = 1.0;
  std::vector<double> sample_times;  // each a multiple of the scene's h
  double blow_up_factor = 10.0;
  bool keep_frame = false;
  // The stability table counts det F <= 0 as a failure for every model; the study measures
  // accuracy and lets the invertible models invert (neo-Hookean never can: the core stops it).
  bool inversion_is_failure = true;
  // With inversion_is_failure: det F <= 0 ends nothing, and a run that otherwise ends ok is
  // inverted-allowed (the models that may invert by design: methods.h's inversion_allowed).
  bool inversion_allowed = false;
};

struct RunResult {
  Verdict verdict = Verdict::Ok;
  long fail_step = -1;  // the step that failed (1-based), or -1
  std::string message;
  double wall_s = 0.0;  // wall-clock seconds inside step() (the checks here are not counted)
  long steps = 0;       // accepted steps
  long newton_iterations = 0;
  double min_det_f = NAN;     // the smallest det F over the run, where inversions are looked at
  std::vector<VecX> samples;  // positions at the sample times reached
  Frame frame;
};

// Steps at the sample times: round(t / h); "" or an error when a time is not a multiple.
std::string sample_steps(const std::vector<double>& times, double h, std::vector<long>* steps);

RunResult run_scene(const SceneDef& scene, const RunOptions& options);

// Number of steps of size h in `duration` (rounded to the nearest integer).
long step_count(double duration, double h);

}  // namespace invfree
