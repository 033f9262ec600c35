// `invfree verify`: every benchmark case (verify_cases.h) on its series of meshes, the
// relative error of each against its exact or reference value, the observed order of
// convergence, and what the command writes: verify.csv, the convergence chart and the table
// it prints (docs/verification.md).
// Inputs: the cases to run and the sweep's options (quick, progress, stop). Outputs: a
// VerifyResult and its texts and chart panels.
#pragma once

#include <string>
#include <vector>

#include "app/plot/chart.h"
#include "app/study/sweep_options.h"
#include "app/verify/verify_cases.h"

namespace invfree {

struct VerifyRow {
  std::string case_name;
  int n_seg = 0;
  CaseRun run;
  // The observed order against the previous mesh of the same case:
  // log(e_i / e_{i-1}) / log(N_i / N_{i-1}) with N the unknowns; NaN on the first mesh, after
  // a failed run and for the exact cases.
  double slope = 0.0;
};

struct VerifyResult {
  std::vector<const VerifyCase*> cases;  // in the order they ran
  std::vector<VerifyRow> rows;           // case by case, coarse to fine
  bool quick = false;
  bool stopped = false;       // Ctrl-C between runs
  double total_wall_s = 0.0;  // in the solver, summed over every run
};

// Parses --cases: "" or "all" for every case, else comma-separated names. Returns "" or a
// one-line error naming the unknown word (with a suggestion).
std::string parse_verify_cases(const std::string& text, std::vector<const VerifyCase*>& cases);

// Runs each case on its levels (quick_levels under options.quick); a progress line per run.
// A scene that does not load is an exception-free failure row naming the reason.
VerifyResult run_verify(const std::vector<const VerifyCase*>& cases, const SweepOptions& options);

// The least-squares slope of log(relative error) against log(unknowns) over a case's rows
// that ran (NaN with fewer than two, and for the exact cases).
double verify_fitted_slope(const VerifyResult& result, const std::string& case_name);
// True when some run failed.
bool verify_failed(const VerifyResult& result);

// case,n_seg,max_edge,unknowns,triangles,computed,reference,relative_error,slope,load_steps,
// newton_iterations,solve_ms,failure (docs/verification.md).
std::string verify_csv(const VerifyResult& result);
// The table the command prints: one line per run, then one per case with its fitted slope.
std::string verify_table(const VerifyResult& result);
// The chart's panels: relative error against unknowns (log-log) of the convergent cases, one
// series each with its fitted slope in the legend and dashed guides of the theoretical
// slopes; the exact cases' errors (rounding) in a panel of their own; when large-strain
// ran, its load path against the closed-form curve. Only the panels of cases that ran.
std::vector<ChartSpec> verify_panels(const VerifyResult& result);

}  // namespace invfree
