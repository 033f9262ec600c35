// `invfree verify`: the simulator against elasticity's exact and reference answers
// (app/verify/verify.h, docs/verification.md). Runs each benchmark case on a series of
// meshes, prints the table (computed, reference, relative error, observed slope), and
// writes DIR/verify.csv and DIR/verify.png (or .svg, .pdf): error against unknowns, log-log.
// Progress goes to stderr. Exit code 3 when a run failed (its row says why; the files are
// written all the same).
#include <cstdio>
#include <string>
#include <vector>

#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/output_files.h"
#include "app/plot/chart.h"
#include "app/sweep_command.h"
#include "app/verify/verify.h"

namespace invfree {

namespace {

struct VerifyCommandOptions {
  SweepCommandOptions sweep;
  std::string cases = "all";
};

int run_verify_command(const VerifyCommandOptions& opt) {
  std::vector<const VerifyCase*> cases;
  if (std::string e = parse_verify_cases(opt.cases, cases); !e.empty())
    return fail(exit_code::kBadInput, e);
  const std::string csv_path = opt.sweep.out + "/verify.csv",
                    chart_path = opt.sweep.out + "/verify." + chart_extension(opt.sweep.format);
  if (auto e = check_output_files({csv_path, chart_path}, {}, opt.sweep.force))
    return fail(e.exit_code, e.message);

  const VerifyResult result = run_verify(cases, sweep_options(opt.sweep, "verify"));
  if (result.stopped) return fail(interrupted_exit_code(), "verify interrupted; nothing written");
  std::string error = write_file_atomically(csv_path, verify_csv(result));
  if (error.empty())
    error = write_canvas(chart_path, *chart_canvas(verify_panels(result), opt.sweep.format));
  if (!error.empty()) return fail(exit_code::kOutputFailed, error);

  std::fputs(verify_table(result).c_str(), stdout);
  int failed = 0;
  for (const VerifyRow& r : result.rows) failed += !r.run.failure.empty();
  std::printf("verify: %zu cases, %zu runs (%d failed), %.1f s in the solver; wrote %s, %s\n",
              result.cases.size(), result.rows.size(), failed, result.total_wall_s,
              csv_path.c_str(), chart_path.c_str());
  for (const VerifyRow& r : result.rows)
    if (!r.run.failure.empty())
      std::fprintf(stderr, "invfree: %s at n_seg %d failed: %s\n", r.case_name.c_str(), r.n_seg,
                   r.run.failure.c_str());
  return failed ? exit_code::kRunFailed : exit_code::kOk;
}

}  // namespace

void register_verify_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<VerifyCommandOptions>(
      app, exit_code, "verify",
      "compare the simulator with elasticity's exact and reference answers on a series of "
      "meshes; write verify.csv and verify.png",
      run_verify_command);
  opt.sweep.out = "verify";
  add_sweep_options(cmd, opt.sweep, "directory for verify.csv and verify.png (or .svg, .pdf)",
                    "fewer and coarser meshes (docs/verification.md)");
  cmd->add_option("--cases", opt.cases,
                  "comma-separated cases to run: " + verify_case_names() + ", or all")
      ->type_name("LIST")
      ->capture_default_str();
}

}  // namespace invfree
