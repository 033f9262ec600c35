// `invfree study`: speed against accuracy of every method on one scene (app/study/study.h).
// Writes DIR/study.csv, DIR/study.png (error against wall time with the Pareto front, and
// error against h with the fitted convergence slope) and DIR/study-sweeps.png (Newton
// tolerance and mesh resolution sweeps). Progress goes to stderr, a summary to stdout.
#include <cmath>
#include <cstdio>
#include <memory>

#include "app/cli_checks.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/output_files.h"
#include "app/plot/chart.h"
#include "app/scene_options.h"
#include "app/study/study.h"
#include "app/study/study_chart.h"

namespace invfree {

namespace {

struct StudyCommandOptions {
  SceneOptions scene;
  std::string out = ".";
  bool quick = false;
  bool quiet = false;
};

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "invfree: %s\n", message.c_str());
  return code;
}

int run_study_command(const StudyCommandOptions& opt) {
  std::string error;
  auto scene = opt.scene.resolve(&error);
  if (!scene) return fail(exit_code::kBadInput, error);
  const std::string csv_path = opt.out + "/study.csv", png_path = opt.out + "/study.png",
                    sweeps_path = opt.out + "/study-sweeps.png";
  for (const std::string& p : {csv_path, png_path, sweeps_path})
    if (auto e = check_output_file(p, opt.scene.input_files())) return fail(e.exit_code, e.message);

  StudyOptions options;
  options.quick = opt.quick;
  if (!opt.quiet)
    options.progress = [](const std::string& line) {
      std::fprintf(stderr, "study: %s\n", line.c_str());
    };
  options.stop = [] { return interrupted(); };
  const StudyResult result = run_study(*scene, options);
  if (result.stopped) return fail(interrupted_exit_code(), "study interrupted; nothing written");

  if (auto e = write_file_atomically(csv_path, study_csv(result)); !e.empty())
    return fail(exit_code::kOutputFailed, e);
  if (auto e = write_png(png_path, study_chart(result)); !e.empty())
    return fail(exit_code::kOutputFailed, e);
  if (auto e = write_png(sweeps_path, sweeps_chart(result)); !e.empty())
    return fail(exit_code::kOutputFailed, e);

  int failed = 0;
  for (const StudyRow& r : result.rows) failed += r.failure != "ok";
  std::printf(
      "study of %s: %zu runs (%d failed), implicit Euler error slope %.2f, %.1f s in the solver; "
      "wrote %s, "
      "%s, %s\n",
      scene->name.c_str(), result.rows.size(), failed, result.lecture_slope, result.total_wall_s,
      csv_path.c_str(), png_path.c_str(), sweeps_path.c_str());
  for (const std::string& f : result.reference_failures)
    std::fprintf(stderr, "invfree: warning: %s\n", f.c_str());
  return exit_code::kOk;
}

}  // namespace

void register_study_command(CLI::App& app, int& exit_code) {
  auto opt = std::make_shared<StudyCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "study",
      "speed against accuracy: sweep h, Newton tol and mesh resolution for every method; write "
      "study.csv, study.png, study-sweeps.png");
  opt->scene.add_to(cmd);
  cmd->add_option("--out", opt->out, "directory for study.csv, study.png and study-sweeps.png")
      ->type_name("DIR")
      ->capture_default_str()
      ->check(non_empty_path());
  cmd->add_flag("--quick", opt->quick, "fewer and shorter runs (under a minute on 2 cores)");
  cmd->add_flag("--quiet", opt->quiet, "no progress lines on stderr");
  cmd->callback([opt, &exit_code] { exit_code = run_study_command(*opt); });
}

}  // namespace invfree
