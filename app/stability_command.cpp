// `invfree stability`: every method on every stress scene (app/study/stability.h).
// Writes DIR/stability.md (the verdict table), DIR/stability.csv and DIR/stability.png
// (the contact sheet). Exit code 3 when the lecture's method is not ok on a scene it can
// run (it must survive them all); other methods failing is the expected result.
// --slides adds stability-slide.png (app/study/stability_summary.h), --methods picks rows.
#include <cstdio>

#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/output_files.h"
#include "app/plot/chart.h"
#include "app/study/contact_sheet.h"
#include "app/study/methods.h"
#include "app/study/stability.h"
#include "app/study/stability_summary.h"
#include "app/sweep_command.h"

namespace invfree {

namespace {

struct StabilityCommandOptions {
  SweepCommandOptions sweep;
  std::string methods;  // --methods a,b,c
  bool slides = false;
};

int run_stability_command(const StabilityCommandOptions& options) {
  const SweepCommandOptions& opt = options.sweep;
  std::vector<std::string> methods;
  if (std::string e = parse_method_list(options.methods, stability_methods(), &methods); !e.empty())
    return fail(exit_code::kBadInput, e);
  const std::string md_path = opt.out + "/stability.md", csv_path = opt.out + "/stability.csv",
                    png_path = opt.out + "/stability." + chart_extension(opt.format),
                    slide_path = opt.out + "/stability-slide." + chart_extension(opt.format);
  if (auto e = check_output_files({md_path, csv_path, png_path}, {}, opt.force))
    return fail(e.exit_code, e.message);
  if (options.slides)
    if (auto e = check_output_files({slide_path}, {}, opt.force))
      return fail(e.exit_code, e.message);

  SweepOptions sweep = sweep_options(opt, "stability");
  sweep.methods = methods;
  const StabilityResult result = run_stability(sweep);
  if (result.stopped)
    return fail(interrupted_exit_code(), "stability interrupted; nothing written");
  for (const std::string& e : result.scene_errors) std::fprintf(stderr, "invfree: %s\n", e.c_str());
  std::string error = write_file_atomically(csv_path, stability_csv(result));
  if (error.empty()) error = write_file_atomically(md_path, stability_markdown(result));
  if (error.empty()) error = write_canvas(png_path, *contact_sheet(result, opt.format));
  if (error.empty() && options.slides)
    error = write_canvas(slide_path, *stability_summary(result, opt.format));
  if (!error.empty()) return fail(exit_code::kOutputFailed, error);

  int ok = 0, failed = 0, na = 0, allowed = 0, lecture_failed = 0;
  for (const StabilityCell& c : result.cells) {
    switch (cell_class(c.verdict)) {
      case CellClass::Ok:
        ++ok;
        break;
      case CellClass::NotApplicable:
        ++na;
        break;
      case CellClass::InversionAllowed:
        ++allowed;
        break;
      case CellClass::Failed:
        ++failed;
        break;
    }
    if (c.method == "lecture" && c.verdict != Verdict::Ok && c.verdict != Verdict::NotApplicable) {
      ++lecture_failed;
      std::fprintf(stderr, "invfree: the lecture's method failed on %s: %s (%s): %s\n",
                   c.scene.c_str(), verdict_name(c.verdict), failure_time(c).c_str(),
                   c.message.c_str());
    }
  }
  std::printf(
      "stability: %zu methods x %zu scenes: %d ok, %d inverted as their model allows, %d "
      "failed, %d n/a; %.1f s in the solver; wrote %s, %s, %s%s\n",
      result.methods.size(), result.scenes.size(), ok, allowed, failed, na, result.total_wall_s,
      md_path.c_str(), csv_path.c_str(), png_path.c_str(),
      options.slides ? (", " + slide_path).c_str() : "");
  if (!result.scene_errors.empty()) return exit_code::kBadInput;
  return lecture_failed ? exit_code::kRunFailed : exit_code::kOk;
}

}  // namespace

void register_stability_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<StabilityCommandOptions>(
      app, exit_code, "stability",
      "run every method on every stress scene; write stability.md, stability.csv, stability.png",
      run_stability_command);
  add_sweep_options(
      cmd, opt.sweep, "directory for stability.md, stability.csv and stability.png (or .svg, .pdf)",
      "each scene only until its defining event (the ceiling stops), without settling");
  cmd->add_option("--methods", opt.methods,
                  "run only these methods (the rows), comma-separated (docs/study.md lists them)");
  cmd->add_flag("--slides", opt.slides,
                "also write stability-slide: the verdicts as one 16:9 grid with large type");
}

}  // namespace invfree
