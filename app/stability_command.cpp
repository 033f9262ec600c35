// `invfree stability`: every method on every stress scene (app/study/stability.h).
// Writes DIR/stability.md (the verdict table), DIR/stability.csv and DIR/stability.png
// (the contact sheet). Exit code 3 when the lecture's method is not ok on a scene it can
// run (it must survive them all); other methods failing is the expected result.
#include <cstdio>

#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/output_files.h"
#include "app/plot/chart.h"
#include "app/study/contact_sheet.h"
#include "app/study/stability.h"
#include "app/sweep_command.h"

namespace invfree {

namespace {

int run_stability_command(const SweepCommandOptions& opt) {
  const std::string md_path = opt.out + "/stability.md", csv_path = opt.out + "/stability.csv",
                    png_path = opt.out + "/stability." + chart_extension(opt.format);
  if (auto e = check_output_files({md_path, csv_path, png_path}, {}, opt.force))
    return fail(e.exit_code, e.message);

  const StabilityResult result = run_stability(sweep_options(opt, "stability"));
  if (result.stopped)
    return fail(interrupted_exit_code(), "stability interrupted; nothing written");
  for (const std::string& e : result.scene_errors) std::fprintf(stderr, "invfree: %s\n", e.c_str());
  std::string error = write_file_atomically(csv_path, stability_csv(result));
  if (error.empty()) error = write_file_atomically(md_path, stability_markdown(result));
  if (error.empty()) error = write_canvas(png_path, *contact_sheet(result, opt.format));
  if (!error.empty()) return fail(exit_code::kOutputFailed, error);

  int ok = 0, failed = 0, na = 0, lecture_failed = 0;
  for (const StabilityCell& c : result.cells) {
    if (c.verdict == Verdict::Ok)
      ++ok;
    else if (c.verdict == Verdict::NotApplicable)
      ++na;
    else
      ++failed;
    if (c.method == "lecture" && c.verdict != Verdict::Ok && c.verdict != Verdict::NotApplicable) {
      ++lecture_failed;
      std::fprintf(stderr, "invfree: the lecture's method failed on %s: %s (%s): %s\n",
                   c.scene.c_str(), verdict_name(c.verdict), failure_time(c).c_str(),
                   c.message.c_str());
    }
  }
  std::printf(
      "stability: %zu methods x %zu scenes: %d ok, %d failed, %d n/a; %.1f s in the solver; wrote "
      "%s, %s, %s\n",
      result.methods.size(), result.scenes.size(), ok, failed, na, result.total_wall_s,
      md_path.c_str(), csv_path.c_str(), png_path.c_str());
  if (!result.scene_errors.empty()) return exit_code::kBadInput;
  return lecture_failed ? exit_code::kRunFailed : exit_code::kOk;
}

}  // namespace

void register_stability_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<SweepCommandOptions>(
      app, exit_code, "stability",
      "run every method on every stress scene; write stability.md, stability.csv, stability.png",
      run_stability_command);
  add_sweep_options(
      cmd, opt, "directory for stability.md, stability.csv and stability.png (or .svg, .pdf)",
      "each scene only until its defining event (the ceiling stops), without settling");
}

}  // namespace invfree
