// `invfree stability`: every method on every stress scene (app/study/stability.h).
// Writes DIR/stability.md (the verdict table), DIR/stability.csv and DIR/stability.png
// (the contact sheet). Exit code 3 when the lecture's method is not ok on a scene it can
// run (it must survive them all); other methods failing is the expected result.
#include <cstdio>
#include <memory>

#include "app/cli_checks.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/output_files.h"
#include "app/plot/chart.h"
#include "app/study/contact_sheet.h"
#include "app/study/stability.h"

namespace invfree {

namespace {

struct StabilityCommandOptions {
  std::string out = ".";
  bool quick = false;
  bool quiet = false;
};

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "invfree: %s\n", message.c_str());
  return code;
}

int run_stability_command(const StabilityCommandOptions& opt) {
  const std::string md_path = opt.out + "/stability.md", csv_path = opt.out + "/stability.csv",
                    png_path = opt.out + "/stability.png";
  for (const std::string& p : {md_path, csv_path, png_path})
    if (auto e = check_output_file(p)) return fail(e.exit_code, e.message);

  StabilityOptions options;
  options.quick = opt.quick;
  if (!opt.quiet)
    options.progress = [](const std::string& line) {
      std::fprintf(stderr, "stability: %s\n", line.c_str());
    };
  options.stop = [] { return interrupted(); };
  const StabilityResult result = run_stability(options);
  if (result.stopped)
    return fail(interrupted_exit_code(), "stability interrupted; nothing written");
  for (const std::string& e : result.scene_errors) std::fprintf(stderr, "invfree: %s\n", e.c_str());

  if (auto e = write_file_atomically(csv_path, stability_csv(result)); !e.empty())
    return fail(exit_code::kOutputFailed, e);
  if (auto e = write_file_atomically(md_path, stability_markdown(result)); !e.empty())
    return fail(exit_code::kOutputFailed, e);
  if (auto e = write_png(png_path, contact_sheet(result)); !e.empty())
    return fail(exit_code::kOutputFailed, e);

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
      std::fprintf(stderr, "invfree: the lecture's method failed on %s: %s at step %ld: %s\n",
                   c.scene.c_str(), verdict_name(c.verdict), c.fail_step, c.message.c_str());
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
  auto opt = std::make_shared<StabilityCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "stability",
      "run every method on every stress scene; write stability.md, stability.csv, stability.png");
  cmd->add_option("--out", opt->out, "directory for stability.md, stability.csv and stability.png")
      ->type_name("DIR")
      ->capture_default_str()
      ->check(non_empty_path());
  cmd->add_flag("--quick", opt->quick, "only the first 2 s of each scene");
  cmd->add_flag("--quiet", opt->quiet, "no progress lines on stderr");
  cmd->callback([opt, &exit_code] { exit_code = run_stability_command(*opt); });
}

}  // namespace invfree
