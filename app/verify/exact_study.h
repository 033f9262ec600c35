// `invfree study`'s chart against the exact answer: speed against accuracy measured
// against elasticity's truth instead of a converged run of the same model. The static
// cantilever of `invfree verify` (verify_cases.h) is solved by every model family (the
// lecture's neo-Hookean, stable neo-Hookean, linear elasticity, ARAP) with each direct
// linear solver (the project's LDL^T, CHOLMOD) on a series of meshes: milliseconds per
// static solve against the tip deflection's relative error to the clamped beam's converged
// value (verify_cases.cpp; Timoshenko's beam theory is 0.34% above it). The
// models that share linear elasticity's small-strain limit converge to it; ARAP, which has
// no volumetric term, converges to a different answer, and the chart shows where it stalls.
// Inputs: the sweep's options (quick: fewer meshes). Outputs: rows, their CSV and a panel.
#pragma once

#include <string>
#include <vector>

#include "app/plot/chart.h"
#include "app/study/sweep_options.h"

namespace invfree {

struct ExactStudyRow {
  std::string model;   // material.model's name
  std::string solver;  // solver.linear_solver's name
  int n_seg = 0;
  int unknowns = 0;
  double solve_ms = 0.0;        // the static solve (all its load steps), meshing excluded
  double relative_error = 0.0;  // NaN when the run failed
  int newton_iterations = 0;
  std::string failure;  // "" when it converged
};

struct ExactStudy {
  std::string case_name;  // "cantilever"
  std::string reference;  // what the error is measured against
  std::vector<ExactStudyRow> rows;
  bool stopped = false;
};

ExactStudy run_exact_study(const SweepOptions& options);
// model,solver,n_seg,unknowns,solve_ms,relative_error,newton_iterations,failure
std::string exact_study_csv(const ExactStudy& study);
// Relative error against ms per solve (log-log), one series per model and solver.
ChartSpec exact_study_panel(const ExactStudy& study);

}  // namespace invfree
