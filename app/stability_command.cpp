// `invfree stability`: every method on every stress scene (app/study/stability.h).
// Writes DIR/stability.md (the verdict table), DIR/stability.csv and the contact sheet's
// 16:9 pages DIR/stability-sheet-1.png, -2, ... (the failed runs and the allowed
// inversions, large: app/study/stability_sheet_pages.h; with --force, pages left from an
// earlier run beyond the new last one are removed). Exit code 3 when the lecture's method
// is not ok on a scene it can run (it must survive them all); other methods failing is the
// expected result. --slides adds stability-slide.png (app/study/stability_summary.h),
// --full-sheet stability.png (every run: app/study/contact_sheet.h), --methods picks rows,
// --scenes columns.
#include <cstdio>
#include <filesystem>
#include <regex>

#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/output_files.h"
#include "app/plot/chart.h"
#include "app/study/contact_sheet.h"
#include "app/study/methods.h"
#include "app/study/stability.h"
#include "app/study/stability_sheet_pages.h"
#include "app/study/stability_summary.h"
#include "app/study/stress_scenes.h"
#include "app/sweep_command.h"

namespace invfree {

namespace {

struct StabilityCommandOptions {
  SweepCommandOptions sweep;
  std::string methods;  // --methods a,b,c
  std::string scenes;   // --scenes a,b
  bool slides = false;
  bool full_sheet = false;
};

// The --scenes list, each a stress scene's name; "" or a one-line error.
std::string parse_scene_list(const std::string& text, std::vector<std::string>* out) {
  out->clear();
  if (text.empty()) return "";
  std::string choices;
  for (const StressScene& s : stress_scenes()) choices += (choices.empty() ? "" : ", ") + s.name;
  size_t begin = 0;
  while (begin <= text.size()) {
    const size_t end = std::min(text.find(',', begin), text.size());
    const std::string name = text.substr(begin, end - begin);
    if (std::none_of(stress_scenes().begin(), stress_scenes().end(),
                     [&](const StressScene& s) { return s.name == name; }))
      return "--scenes: unknown scene '" + name + "' (one of: " + choices + ")";
    out->push_back(name);
    begin = end + 1;
  }
  return "";
}

std::string sheet_page_path(const std::string& dir, size_t page, ChartFormat format) {
  return dir + "/stability-sheet-" + std::to_string(page) + "." + chart_extension(format);
}

// The sheet's pages already in `dir` (stability-sheet-<n>.<ext>), by number.
std::vector<std::pair<size_t, std::string>> existing_sheet_pages(const std::string& dir,
                                                                 ChartFormat format) {
  std::vector<std::pair<size_t, std::string>> pages;
  const std::regex name("stability-sheet-([1-9][0-9]{0,5})\\." +
                        std::string(chart_extension(format)));
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    std::smatch m;
    const std::string file = e.path().filename().string();
    if (std::regex_match(file, m, name))
      pages.emplace_back(std::stoul(m[1]), sheet_page_path(dir, std::stoul(m[1]), format));
  }
  return pages;
}

int run_stability_command(const StabilityCommandOptions& options) {
  const SweepCommandOptions& opt = options.sweep;
  std::vector<std::string> methods;
  if (std::string e = parse_method_list(options.methods, stability_methods(), &methods); !e.empty())
    return fail(exit_code::kBadInput, e);
  std::vector<std::string> scenes;
  if (std::string e = parse_scene_list(options.scenes, &scenes); !e.empty())
    return fail(exit_code::kBadInput, e);
  const std::string md_path = opt.out + "/stability.md", csv_path = opt.out + "/stability.csv",
                    png_path = opt.out + "/stability." + chart_extension(opt.format),
                    slide_path = opt.out + "/stability-slide." + chart_extension(opt.format);
  if (auto e = check_output_files({md_path, csv_path, sheet_page_path(opt.out, 1, opt.format)}, {},
                                  opt.force))
    return fail(e.exit_code, e.message);
  // Every page an earlier run left is this run's output too: replaced or removed.
  const auto old_pages = existing_sheet_pages(opt.out, opt.format);
  for (const auto& [number, path] : old_pages)
    if (auto e = check_output_files({path}, {}, opt.force)) return fail(e.exit_code, e.message);
  if (options.slides)
    if (auto e = check_output_files({slide_path}, {}, opt.force))
      return fail(e.exit_code, e.message);
  if (options.full_sheet)
    if (auto e = check_output_files({png_path}, {}, opt.force)) return fail(e.exit_code, e.message);

  SweepOptions sweep = sweep_options(opt, "stability");
  sweep.methods = methods;
  sweep.scenes = scenes;
  const StabilityResult result = run_stability(sweep);
  if (result.stopped)
    return fail(interrupted_exit_code(), "stability interrupted; nothing written");
  for (const std::string& e : result.scene_errors) std::fprintf(stderr, "invfree: %s\n", e.c_str());
  std::string error = write_file_atomically(csv_path, stability_csv(result));
  if (error.empty()) error = write_file_atomically(md_path, stability_markdown(result));
  const std::vector<SheetPage> pages = stability_sheet_pages(result, opt.format);
  for (size_t p = 0; p < pages.size() && error.empty(); ++p)
    error = write_canvas(sheet_page_path(opt.out, p + 1, opt.format), *pages[p].canvas);
  for (const auto& [number, path] : old_pages)
    if (error.empty() && number > pages.size()) {
      std::error_code ec;
      if (!std::filesystem::remove(path, ec) && ec)
        error = path + ": cannot remove a page of an earlier run: " + ec.message();
    }
  if (error.empty() && options.full_sheet)
    error = write_canvas(png_path, *contact_sheet(result, opt.format));
  if (error.empty() && options.slides)
    error = write_canvas(slide_path, *stability_summary(result, opt.format));
  if (!error.empty()) return fail(exit_code::kOutputFailed, error);

  const std::string pages_written =
      sheet_page_path(opt.out, 1, opt.format) +
      (pages.size() > 1 ? " to -" + std::to_string(pages.size()) + "." + chart_extension(opt.format)
                        : "");
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
      "failed, %d n/a; %.1f s in the solver; wrote %s, %s, %s%s%s\n",
      result.methods.size(), result.scenes.size(), ok, allowed, failed, na, result.total_wall_s,
      md_path.c_str(), csv_path.c_str(), pages_written.c_str(),
      options.full_sheet ? (", " + png_path).c_str() : "",
      options.slides ? (", " + slide_path).c_str() : "");
  if (!result.scene_errors.empty()) return exit_code::kBadInput;
  return lecture_failed ? exit_code::kRunFailed : exit_code::kOk;
}

}  // namespace

void register_stability_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<StabilityCommandOptions>(
      app, exit_code, "stability",
      "run every method on every stress scene; write stability.md, stability.csv and the "
      "contact sheet's pages stability-sheet-N.png",
      run_stability_command);
  add_sweep_options(
      cmd, opt.sweep,
      "directory for stability.md, stability.csv and stability-sheet-N.png (or .svg, .pdf)",
      "each scene only until its defining event (the ceiling stops), without settling");
  cmd->add_option("--methods", opt.methods,
                  "run only these methods (the rows), comma-separated (docs/study.md lists them)");
  cmd->add_option("--scenes", opt.scenes,
                  "run only these stress scenes (the columns), comma-separated (docs/study.md "
                  "lists them)");
  cmd->add_flag("--full-sheet", opt.full_sheet,
                "also write stability.png: the contact sheet of every run (a row per method, a "
                "column per scene)");
  cmd->add_flag("--slides", opt.slides,
                "also write stability-slide: the verdicts as one 16:9 grid with large type");
}

}  // namespace invfree
