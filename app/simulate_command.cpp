// `invfree simulate`: steps a scene headlessly and writes the per-step table (--csv) and
// the deformed mesh (--obj). Prints a one-line summary on stdout. Every output file is
// written atomically; Ctrl-C stops between steps and keeps what is complete (exit 130).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <utility>

#include "app/cli_checks.h"
#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/output_files.h"
#include "app/scene_options.h"
#include "collision/intersection_check.h"
#include "energy_report.h"
#include "scene/boundary.h"
#include "simulation.h"

namespace invfree {

namespace {

struct SimulateOptions {
  SceneOptions scene;
  int steps = 300;
  std::string obj_dir;
  std::string csv_path;
  bool force = false;
};

std::string obj_text(const Simulation& sim) {
  std::ostringstream o;
  o.precision(17);
  for (int i = 0; i < sim.mesh.node_count(); ++i)
    o << "v " << sim.x[2 * i] << " " << sim.x[2 * i + 1] << " 0.0\n";
  for (const auto& t : sim.mesh.triangles)
    o << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  return o.str();
}

// The range of det F over the triangles; NaN for a mesh without triangles (particles).
std::pair<double, double> det_f_range(const Simulation& sim) {
  const auto det = triangle_det_f(sim);
  if (det.empty()) return {std::nan(""), std::nan("")};
  const auto [lo, hi] = std::minmax_element(det.begin(), det.end());
  return {*lo, *hi};
}

// Watches a run without self-contact (switched off, or unable to run: scene.h) for its
// boundary crossing itself: the exact check of collision/intersection_check.h on every
// accepted state, and one warning on stderr at the first crossing. With self-contact on,
// the step's invariant already keeps every state free of crossings.
class CrossingWatch {
 public:
  explicit CrossingWatch(const Simulation& sim)
      : on_(!sim.scene.self_contact_on() && sim.mesh.triangle_count() > 0) {
    if (on_) boundary_ = find_boundary(sim.mesh);
  }
  // Whether the state just accepted crosses itself; warns the first time.
  bool check(const Simulation& sim) {
    if (!on_) return false;
    const auto hit = find_self_intersection(boundary_, sim.x, grid_, scratch_);
    if (hit && !warned_) {
      warned_ = true;
      const auto& a = boundary_.edges[hit->edge_a];
      const auto& b = boundary_.edges[hit->edge_b];
      std::fprintf(stderr,
                   "invfree: warning: step %ld: boundary edges %d-%d and %d-%d cross: without "
                   "self-contact the boundary passes through itself (the CSV's "
                   "self_intersecting column flags every such step)\n",
                   sim.step_count, a[0], a[1], b[0], b[1]);
    }
    return hit.has_value();
  }
  bool warned() const { return warned_; }

 private:
  bool on_;
  bool warned_ = false;
  Boundary boundary_;
  BroadPhaseGrid grid_;
  std::vector<std::array<int, 2>> scratch_;
};

// The CSV row of the step just taken (the columns of --csv).
void write_csv_row(std::ostream& csv, const Simulation& sim, const StepReport& r,
                   bool self_intersecting) {
  const auto [lo, hi] = det_f_range(sim);
  const double gap = min_plane_gap(sim);
  csv << sim.step_count << "," << sim.time << "," << r.newton_iterations << "," << r.residual << ","
      << r.energy << "," << lo << "," << hi << "," << (std::isfinite(gap) ? gap : -1.0) << ","
      << (sim.scene.has_ceiling ? sim.ceiling_y : 0.0) << ",";
  const EnergyReport e = energy_report(sim);
  csv << e.kinetic << "," << e.elastic << "," << e.gravitational << "," << e.contact << ",";
  const double self_gap = min_self_gap(sim);  // -1: no pair within dhat (or no self-contact)
  csv << (std::isfinite(self_gap) ? self_gap : -1.0) << "," << (self_intersecting ? 1 : 0) << ","
      << r.wall_ms << "\n";
}

// The range of det F over every state of the run: the initial one and each accepted step's
// (a step whose det F is not finite fails, so the range is of numbers).
struct RunDetFRange {
  double lo = INFINITY, hi = -INFINITY;
  void add(const Simulation& sim) {
    if (sim.mesh.triangle_count() == 0) return;
    const auto [l, h] = det_f_range(sim);
    lo = std::min(lo, l);
    hi = std::max(hi, h);
  }
};

// det F for people: four decimals, or four significant digits where that would be long.
std::string det_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, std::abs(v) < 1e5 ? "%.4f" : "%.4g", v);
  return buf;
}

// The one-line summary on stdout: steps, time, mean Newton iterations and ms per step,
// the range of det F over the run (every state from step 0 on).
void print_summary(const Simulation& sim, const RunDetFRange& range, long total_iterations,
                   double total_ms) {
  const long done = sim.step_count;
  std::string det = "no triangles";
  if (sim.mesh.triangle_count() > 0)
    det = "det F in [" + det_text(range.lo) + ", " + det_text(range.hi) + "] over steps 0.." +
          std::to_string(done);
  std::printf("%s: %ld steps, t = %.3f s, %.2f Newton iterations/step, %.3f ms/step, %s\n",
              sim.scene.name.c_str(), done, sim.time,
              done ? double(total_iterations) / done : 0.0, done ? total_ms / done : 0.0,
              det.c_str());
  flush_standard_output();
}

// Which step failed, how and when, and what the outputs hold.
std::string step_failure_message(const Simulation& sim, const StepReport& failure) {
  const long done = sim.step_count;
  char t[32];
  std::snprintf(t, sizeof t, "%.4g", sim.time + sim.scene.h);
  return "step " + std::to_string(done + 1) + " failed: " + step_status_name(failure.status) +
         ": " + failure.message + " (t = " + t + " s); outputs hold steps 0.." +
         std::to_string(done);
}

int run_simulate(const SimulateOptions& opt) {
  std::string error;
  auto scene = opt.scene.resolve(&error);
  if (!scene) return fail(exit_code::kBadInput, error);
  // Check every output before the first step: a long run must not fail at its end. The
  // OBJ directory is locked and found empty before the CSV's temporary file is made
  // (which may be in it: --csv DIR/run.csv).
  if (auto e = check_outputs_apart({{"--csv", opt.csv_path}}, {{"--obj", opt.obj_dir}}))
    return fail(e.exit_code, e.message);
  if (!opt.csv_path.empty())
    if (auto e = check_output_files({opt.csv_path}, opt.scene.input_files(), opt.force))
      return fail(e.exit_code, e.message);
  OutputDirectory obj_dir;
  if (!opt.obj_dir.empty())
    if (auto e = obj_dir.open(opt.obj_dir, opt.force)) return fail(e.exit_code, e.message);
  AtomicFileWriter csv_file;
  if (!opt.csv_path.empty())
    if (auto e = csv_file.open(opt.csv_path); !e.empty()) return fail(exit_code::kOutputFailed, e);

  Simulation sim = make_simulation(*scene);
  auto write_obj = [&]() -> std::string {
    if (opt.obj_dir.empty()) return "";
    return write_file_atomically(opt.obj_dir + "/" + std::to_string(sim.step_count) + ".obj",
                                 obj_text(sim));
  };

  // CSV rows go to the temporary file in chunks, so memory stays flat however long the run.
  std::ostringstream csv;
  csv.precision(10);
  csv << "step,t,newton_iters,residual,incremental_potential,min_det_F,max_det_F,min_gap,ceiling_y,"
         "kinetic,elastic,gravitational,contact,min_self_gap,self_intersecting,wall_ms\n";
  auto flush_csv = [&](bool force_flush) -> std::string {
    if (!csv_file.is_open() || (!force_flush && csv.tellp() < (1 << 16))) return "";
    const std::string chunk = csv.str();
    csv.str("");
    return csv_file.append(chunk);
  };

  long total_iterations = 0;
  double total_ms = 0.0;
  StepReport failure;
  // An OBJ that cannot be written (a full disk) ends the run with exit 4 but, as a failed
  // step or Ctrl-C does, keeps the CSV complete for the steps whose OBJ was written.
  std::string obj_error = write_obj();
  CrossingWatch crossings(sim);
  RunDetFRange det_range;
  det_range.add(sim);
  for (int k = 0; obj_error.empty() && k < opt.steps && !interrupted(); ++k) {
    const StepReport r = step(sim);
    if (r.status != StepStatus::Ok) {
      if (!interrupted()) failure = r;  // else a signal stopped Newton: an interruption
      break;
    }
    det_range.add(sim);
    total_iterations += r.newton_iterations;
    total_ms += r.wall_ms;
    // After the warning only the CSV needs the check.
    const bool crossing = (!crossings.warned() || csv_file.is_open()) && crossings.check(sim);
    if (obj_error = write_obj(); !obj_error.empty()) break;
    write_csv_row(csv, sim, r, crossing);
    if (auto e = flush_csv(false); !e.empty()) return fail(exit_code::kOutputFailed, e);
  }
  // The table is complete for the steps kept, also after a failure or an interruption.
  if (csv_file.is_open()) {
    std::string e = flush_csv(true);
    if (e.empty()) e = csv_file.commit();
    if (!e.empty())
      return fail(exit_code::kOutputFailed, obj_error.empty() ? e : obj_error + "; " + e);
  }
  if (!obj_error.empty()) {
    const long kept = sim.step_count - 1;
    return fail(exit_code::kOutputFailed,
                obj_error + (kept >= 0 ? "; outputs hold steps 0.." + std::to_string(kept) : ""));
  }
  const long done = sim.step_count;
  print_summary(sim, det_range, total_iterations, total_ms);
  if (failure.status != StepStatus::Ok)
    return fail(exit_code::kRunFailed, step_failure_message(sim, failure));
  if (interrupted())
    return fail(interrupted_exit_code(), "interrupted after step " + std::to_string(done) +
                                             "; outputs hold steps 0.." + std::to_string(done));
  return exit_code::kOk;
}

}  // namespace

void register_simulate_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<SimulateOptions>(
      app, exit_code, "simulate", "step a scene without drawing; write CSV and OBJ files",
      run_simulate);
  opt.scene.add_to(cmd);
  cmd->add_option("--steps", opt.steps, "number of time steps (0 to 100000000)")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000000));
  cmd->add_option(
         "--obj", opt.obj_dir,
         "write DIR/<k>.obj after k steps (k = 0 is the initial mesh); DIR must be empty or new")
      ->type_name("DIR")
      ->check(non_empty_path());
  cmd->add_option("--csv", opt.csv_path,
                  "write one row per step: step,t,newton_iters,residual,incremental_potential,"
                  "min_det_F,max_det_F,min_gap,ceiling_y,kinetic,elastic,gravitational,contact,"
                  "min_self_gap,self_intersecting,wall_ms (energies in J; docs/outputs.md)")
      ->type_name("FILE")
      ->check(non_empty_path());
  cmd->add_flag("--force", opt.force,
                "overwrite an existing --csv file; write into a non-empty --obj directory");
}

}  // namespace invfree
