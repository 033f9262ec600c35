#include "app/study/stability.h"

#include <cmath>
#include <sstream>

#include "app/format_number.h"
#include "app/study/methods.h"
#include "app/study/stress_scenes.h"
#include "scene_io/builtin_scenes.h"

namespace invfree {

std::string failure_time(const StabilityCell& c) {
  return "t = " + format_number(c.fail_step * c.h, "%.3g") + " s, " +
         (c.substeps > 1 ? "substep " : "step ") + format_for_people(c.fail_step) +
         (c.substeps > 1 ? " of h/" + std::to_string(c.substeps) : "");
}

CellClass cell_class(Verdict v) {
  switch (v) {
    case Verdict::Ok:
      return CellClass::Ok;
    case Verdict::InvertedAllowed:
      return CellClass::InversionAllowed;
    case Verdict::NotApplicable:
      return CellClass::NotApplicable;
    default:
      return CellClass::Failed;
  }
}

namespace {

constexpr ExplicitRow kExplicitRows[] = {
    {"course-0-mass-spring", 0.01, 0.83},
    {"course-0-mass-spring", 0.03, 2.50},
};

}  // namespace

// One explicit row: the built-in scene at the row's h, run and classified as every cell.
StabilityCell run_explicit_row(const ExplicitRow& row, bool quick) {
  StabilityCell cell;
  cell.method = explicit_row_method(row);
  cell.scene = row.scene;
  cell.h = row.h;
  const SceneLoad load = load_builtin_scene(row.scene);
  if (!load.scene) {
    cell.verdict = Verdict::NotApplicable;
    cell.fail_step = 0;
    cell.message = load.error;
    return cell;
  }
  SceneDef scene = *load.scene;
  scene.h = row.h;
  RunOptions run;
  run.duration = quick ? quick_stability_duration(scene) : stability_duration(scene);
  const RunResult r = run_scene(scene, run);
  cell.verdict = r.verdict;
  cell.fail_step = r.fail_step;
  cell.wall_s = r.wall_s;
  cell.steps = r.steps;
  cell.duration = run.duration;
  cell.message = r.message;
  return cell;
}

std::span<const ExplicitRow> explicit_rows() {
  return kExplicitRows;
}

std::string explicit_row_method(const ExplicitRow& row) {
  return "chapter-0-explicit-h" + format_number(row.h);
}

StabilityResult run_stability(const SweepOptions& options) {
  StabilityResult result;
  result.quick = options.quick;
  for (const Method& m : stability_methods()) {
    if (!options.wants(m.name)) continue;
    result.methods.push_back(m.name);
    result.method_labels.push_back(m.label);
  }
  std::vector<std::optional<SceneDef>> scenes;
  for (const StressScene& s : stress_scenes()) {
    if (!options.wants_scene(s.name)) continue;
    std::string error;
    scenes.push_back(load_stress_scene(s, &error));
    if (!scenes.back()) result.scene_errors.push_back(error);
    result.scenes.push_back(s.name);
    result.scene_labels.push_back(s.label);
  }
  for (const Method& m : stability_methods()) {
    if (!options.wants(m.name)) continue;
    for (size_t k = 0; k < scenes.size(); ++k) {
      if (options.stop_requested()) {
        result.stopped = true;
        return result;
      }
      StabilityCell cell;
      cell.method = m.name;
      cell.scene = result.scenes[k];
      if (!scenes[k]) {
        cell.verdict = Verdict::NotApplicable;
        cell.fail_step = 0;
        cell.message = "the scene file does not load";
        result.cells.push_back(cell);
        continue;
      }
      SceneDef scene = *scenes[k];
      RunOptions run;
      run.duration = options.quick ? quick_stability_duration(scene) : stability_duration(scene);
      run.keep_frame = true;
      run.inversion_allowed = inversion_allowed(m);
      if (std::string e = apply_method(m, scene, true); !e.empty()) {
        cell.verdict = Verdict::NotApplicable;
        cell.fail_step = 0;
        cell.message = e;
        result.cells.push_back(cell);
        continue;
      }
      const RunResult r = run_scene(scene, run);
      cell.verdict = r.verdict;
      cell.fail_step = r.fail_step;
      cell.wall_s = r.wall_s;
      cell.h = scene.h;
      cell.substeps = m.substeps;
      cell.steps = r.steps;
      cell.duration = run.duration;
      cell.message = r.message;
      cell.min_det_f = r.min_det_f;
      cell.frame = r.frame;
      result.total_wall_s += r.wall_s;
      options.report(std::string(m.name) + " on " + cell.scene + ": " + verdict_name(r.verdict) +
                     (r.verdict == Verdict::Ok ? "" : " (" + failure_time(cell) + ")") + " (" +
                     format_for_people(r.steps) + " steps of " + format_number(scene.h) + " s, " +
                     format_number(r.wall_s) + " s)" + (r.message.empty() ? "" : ": " + r.message));
      result.cells.push_back(std::move(cell));
    }
  }
  for (const ExplicitRow& row : explicit_rows()) {
    if (options.stop_requested()) {
      result.stopped = true;
      return result;
    }
    StabilityCell cell = run_explicit_row(row, options.quick);
    result.total_wall_s += cell.wall_s;
    options.report(cell.method + " on " + cell.scene + ": " + verdict_name(cell.verdict) +
                   (cell.verdict == Verdict::Ok ? "" : " (" + failure_time(cell) + ")") +
                   (cell.message.empty() ? "" : ": " + cell.message));
    result.explicit_cells.push_back(std::move(cell));
  }
  return result;
}

std::string stability_csv(const StabilityResult& r) {
  std::ostringstream o;
  o << "method,scene,verdict,fail_step,wall_s\n";
  for (const auto* cells : {&r.cells, &r.explicit_cells})
    for (const StabilityCell& c : *cells)
      o << c.method << "," << c.scene << "," << verdict_name(c.verdict) << ","
        << (c.verdict == Verdict::Ok ? std::string() : std::to_string(c.fail_step)) << ","
        << format_number(c.wall_s, "%.6g") << "\n";
  return o.str();
}

std::string stability_markdown(const StabilityResult& r) {
  std::ostringstream o;
  o << "# Where methods fail: `invfree stability`\n\n"
    << "Each row is a method, each column a stress scene (`assets/scenes/<scene>.toml`). A cell is "
       "`ok`, or "
       "the verdict and when the run failed, in scene time and in the method's own steps "
       "(`n/a`: the method cannot start the scene). A model that may invert by design (linear, "
       "ARAP, stable neo-Hookean) is not failed for det F <= 0: its run goes on, and a run that "
       "ends without failing says `ok, inverted as the model allows` and when it first "
       "inverted. "
       "Symplectic Euler takes 20 steps per scene step.\n\n";
  if (r.quick)
    o << "**A quick run** (`--quick`): each scene ran until its defining event (the ceiling "
         "reaching its stop), without the 0.5 s to settle after it that a full run adds.\n\n";
  o << "| method |";
  for (const std::string& s : r.scenes) o << " `" << s << "` |";
  o << "\n|---|";
  for (size_t k = 0; k < r.scenes.size(); ++k) o << "---|";
  o << "\n";
  for (size_t m = 0; m < r.methods.size(); ++m) {
    o << "| " << r.methods[m] << " |";
    for (size_t k = 0; k < r.scenes.size(); ++k) {
      const StabilityCell& c = r.at(m, k);
      if (c.verdict == Verdict::Ok)
        o << " ok |";
      else if (c.verdict == Verdict::NotApplicable)
        o << " n/a |";
      else if (c.verdict == Verdict::InvertedAllowed)
        o << " ok, inverted as the model allows (" << failure_time(c) << ") |";
      else
        o << " **" << verdict_name(c.verdict) << "** (" << failure_time(c) << ") |";
    }
    o << "\n";
  }
  if (!r.explicit_cells.empty()) {
    o << "\nThe course's chapter 0, explicit symplectic Euler (the scene's own integrator) on "
         "the hanging mass-spring square at the demo's h and at a larger one: stable only "
         "while omega_max h <= 2 (omega_max = 83.3 rad/s at rest, so h <= 0.024 s):\n\n"
      << "| row | scene | h | omega_max h | verdict |\n|---|---|---:|---:|---|\n";
    for (size_t k = 0; k < r.explicit_cells.size(); ++k) {
      const StabilityCell& c = r.explicit_cells[k];
      const double omega_h = k < explicit_rows().size() ? explicit_rows()[k].omega_h : 0.0;
      o << "| " << c.method << " | `" << c.scene << "` | " << format_number(c.h) << " s | "
        << format_number(omega_h, "%.2f") << " | "
        << (c.verdict == Verdict::Ok ? std::string("ok")
                                     : "**" + std::string(verdict_name(c.verdict)) + "** (" +
                                           failure_time(c) + ")")
        << " |\n";
    }
  }
  o << "\nScenes:\n\n";
  for (size_t k = 0; k < r.scenes.size(); ++k)
    o << "- `" << r.scenes[k] << "`: " << r.scene_labels[k] << "\n";
  o << "\nMethods (each is only scene settings, `--set` on any command):\n\n";
  for (const Method& m : stability_methods())
    o << "- `" << m.name << "`: " << m.label << " — `" << method_command_line(m) << "`"
      << (m.substeps > 1 ? " with h / " + std::to_string(m.substeps) : "") << "\n";
  o << "\nWall-clock seconds inside the solver for each whole run:\n\n| method |";
  for (const std::string& s : r.scenes) o << " `" << s << "` |";
  o << "\n|---|";
  for (size_t k = 0; k < r.scenes.size(); ++k) o << "---:|";
  o << "\n";
  for (size_t m = 0; m < r.methods.size(); ++m) {
    o << "| " << r.methods[m] << " |";
    for (size_t k = 0; k < r.scenes.size(); ++k) {
      const StabilityCell& c = r.at(m, k);
      o << " "
        << (c.verdict == Verdict::NotApplicable ? std::string("–")
                                                : format_number(c.wall_s, "%.3f"))
        << " |";
    }
    o << "\n";
  }
  o << "\nWhy each failing run stopped (and where an allowed inversion came first):\n\n";
  for (const auto* cells : {&r.cells, &r.explicit_cells})
    for (const StabilityCell& c : *cells)
      if (c.verdict != Verdict::Ok)
        o << "- " << c.method << " on `" << c.scene << "`: " << verdict_name(c.verdict)
          << (c.verdict == Verdict::NotApplicable ? "" : " (" + failure_time(c) + ")") << ": "
          << c.message << "\n";
  for (const std::string& e : r.scene_errors) o << "- scene file error: " << e << "\n";
  return o.str();
}

}  // namespace invfree
