// `invfree study`: speed against accuracy of every method on one scene (app/study/study.h).
// Writes DIR/study.csv, DIR/study.png (error against wall time with the Pareto front, and
// error against h with the fitted convergence slope) and DIR/study-sweeps.png (Newton
// tolerance and mesh resolution sweeps), and the error against the exact answer: every model
// family's static cantilever against beam theory (app/verify/exact_study.h), a panel of
// study.png and DIR/study-exact.csv; and the course's chapter 9: the reduced bases' error to
// the full model against ms per step (app/study/reduced_study.h), a panel of study.png and
// DIR/study-reduced.csv. --slides adds the 16:9 slides (app/study/study_slides.h),
// --methods runs a subset. Progress goes to stderr, a summary to stdout, and a warning on
// stdout when a model's errors do not fall with h.
#include <cmath>
#include <cstdio>
#include <string>

#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/format_number.h"
#include "app/interrupt.h"
#include "app/output_files.h"
#include "app/plot/chart.h"
#include "app/scene_options.h"
#include "app/study/reduced_study.h"
#include "app/study/study.h"
#include "app/study/study_chart.h"
#include "app/study/study_slides.h"
#include "app/study/methods.h"
#include "app/sweep_command.h"
#include "app/verify/exact_study.h"

namespace invfree {

namespace {

struct StudyCommandOptions {
  SceneOptions scene;
  SweepCommandOptions sweep;
  std::string methods;  // --methods a,b,c
  bool slides = false;
};

int run_study_command(const StudyCommandOptions& opt) {
  std::string error;
  auto scene = opt.scene.resolve(&error);
  if (!scene) return fail(exit_code::kBadInput, error);
  std::vector<std::string> methods;
  if (std::string e = parse_method_list(opt.methods, study_methods(), &methods); !e.empty())
    return fail(exit_code::kBadInput, e);
  const std::string csv_path = opt.sweep.out + "/study.csv",
                    exact_path = opt.sweep.out + "/study-exact.csv",
                    reduced_path = opt.sweep.out + "/study-reduced.csv",
                    ext = chart_extension(opt.sweep.format),
                    png_path = opt.sweep.out + "/study." + ext,
                    sweeps_path = opt.sweep.out + "/study-sweeps." + ext;
  if (auto e = check_output_files({csv_path, exact_path, reduced_path, png_path, sweeps_path},
                                  opt.scene.input_files(), opt.sweep.force))
    return fail(e.exit_code, e.message);
  if (opt.slides)
    for (const char* n : {"study-slide-speed", "study-slide-convergence"})
      if (auto e = check_output_files({opt.sweep.out + "/" + n + "." + ext},
                                      opt.scene.input_files(), opt.sweep.force))
        return fail(e.exit_code, e.message);

  SweepOptions sweep = sweep_options(opt.sweep, "study");
  sweep.methods = methods;
  const StudyResult result = run_study(*scene, sweep);
  if (result.stopped) return fail(interrupted_exit_code(), "study interrupted; nothing written");
  const ExactStudy exact = run_exact_study(sweep);
  if (exact.stopped) return fail(interrupted_exit_code(), "study interrupted; nothing written");
  const ReducedStudy reduced = run_reduced_study(sweep);
  if (reduced.stopped) return fail(interrupted_exit_code(), "study interrupted; nothing written");
  std::vector<ChartSpec> panels = study_panels(result);
  panels.push_back(exact_study_panel(exact));
  panels.push_back(reduced_study_panel(reduced));
  error = write_file_atomically(csv_path, study_csv(result));
  if (error.empty()) error = write_file_atomically(exact_path, exact_study_csv(exact));
  if (error.empty()) error = write_file_atomically(reduced_path, reduced_study_csv(reduced));
  if (error.empty()) error = write_canvas(png_path, *chart_canvas(panels, opt.sweep.format));
  if (error.empty())
    error = write_canvas(sweeps_path, *chart_canvas(sweeps_panels(result), opt.sweep.format));
  std::string slides_written;
  if (opt.slides)
    for (const Slide& slide : study_slides(result)) {
      const std::string path = opt.sweep.out + "/" + slide.name + "." + ext;
      if (error.empty()) error = write_canvas(path, *chart_canvas({slide.chart}, opt.sweep.format));
      slides_written += ", " + path;
    }
  if (!error.empty()) return fail(exit_code::kOutputFailed, error);

  int failed = 0;
  for (const StudyRow& r : result.rows) failed += r.failure != "ok";
  const std::string slope = std::isfinite(result.lecture_slope)
                                ? format_number(result.lecture_slope, "%.2f")
                                : std::string("none (no run to fit)");
  std::printf(
      "study of %s: %zu runs (%d failed), implicit Euler error slope %s, %.1f s in the solver; "
      "%zu static solves against the exact answer; %zu runs of reduced bases; wrote %s, %s, "
      "%s, %s, %s%s\n",
      scene->name.c_str(), result.rows.size(), failed, slope.c_str(), result.total_wall_s,
      exact.rows.size(), reduced.rows.size(), csv_path.c_str(), exact_path.c_str(),
      reduced_path.c_str(), png_path.c_str(), sweeps_path.c_str(), slides_written.c_str());
  // Errors that do not fall with h rank nothing: said where the summary is read.
  for (const ModelConvergence* c : non_converging_models(result))
    std::printf(
        "warning: the %s errors do not converge with h (%s ... %s of the side, fitted slope "
        "%s): they measure drift from the reference, not accuracy; study.%s draws no Pareto "
        "front for %s\n",
        c->model.c_str(), format_number(c->error_lo, "%.2g").c_str(),
        format_number(c->error_hi, "%.2g").c_str(), format_number(c->slope, "%.2f").c_str(),
        ext.c_str(), c->model.c_str());
  for (const std::string& f : result.reference_failures)
    std::fprintf(stderr, "invfree: warning: %s\n", f.c_str());
  flush_standard_output();
  if (every_run_failed(result)) {
    // The first failure says why (they usually share it).
    std::string first;
    for (const StudyRow& r : result.rows)
      if (r.failure != "ok" && r.failure != "n/a") {
        first = r.method + " at h = " + format_number(r.h, "%.4g") + " s: " + r.failure +
                (r.fail_step > 0 ? " at step " + std::to_string(r.fail_step) : "") +
                (r.message.empty() ? "" : " (" + r.message + ")");
        break;
      }
    return fail(exit_code::kRunFailed,
                "study of " + scene->name + ": every run failed" +
                    (first.empty() ? "" : "; the first: " + first) + "; the charts say so");
  }
  return exit_code::kOk;
}

}  // namespace

void register_study_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<StudyCommandOptions>(
      app, exit_code, "study",
      "speed against accuracy: sweep h, Newton tol and mesh resolution for every method, and "
      "every model's static cantilever against the exact answer, and the reduced bases against "
      "the full model; write study.csv, study-exact.csv, study-reduced.csv, study.png, "
      "study-sweeps.png",
      run_study_command);
  opt.scene.add_to(cmd);
  add_sweep_options(cmd, opt.sweep,
                    "directory for study.csv, study-exact.csv, study-reduced.csv, study.png and "
                    "study-sweeps.png (or .svg, .pdf)",
                    "fewer h, tolerances and meshes, a coarser reference, and fewer reduced bases, "
                    "over the full study's simulated time (docs/study.md)");
  cmd->add_option("--methods", opt.methods,
                  "run only these methods, comma-separated (e.g. lecture,no-projection,"
                  "symplectic-euler; docs/study.md lists them)");
  cmd->add_flag("--slides", opt.slides,
                "also write study-slide-speed and study-slide-convergence: one 16:9 chart each, "
                "large type, the takeaway as the title");
}

}  // namespace invfree
