// `invfree simulate`: steps a scene headlessly and writes the per-step table (--csv) and
// the deformed mesh (--obj). Prints a one-line summary on stdout.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/output_files.h"
#include "app/scene_options.h"
#include "core/simulation.h"

namespace invfree {

namespace {

struct SimulateOptions {
  SceneOptions scene;
  int steps = 300;
  std::string obj_dir;
  std::string csv_path;
};

std::string obj_text(const Simulation& sim) {
  std::ostringstream o;
  o.precision(17);
  for (int i = 0; i < sim.mesh.node_count(); ++i)
    o << "v " << sim.x[2 * i] << " " << sim.x[2 * i + 1] << " 0.0\n";
  for (const auto& t : sim.mesh.triangles) o << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  return o.str();
}

int run_simulate(const SimulateOptions& opt) {
  std::string error;
  auto scene = opt.scene.resolve(&error);
  if (!scene) {
    std::fprintf(stderr, "invfree: %s\n", error.c_str());
    return exit_code::kBadInput;
  }
  if (!opt.obj_dir.empty()) {
    if (auto e = prepare_output_directory(opt.obj_dir, false, true); !e.empty()) {
      std::fprintf(stderr, "invfree: %s\n", e.c_str());
      return exit_code::kOutputFailed;
    }
  }
  Simulation sim = make_simulation(*scene);
  auto write_obj = [&]() -> bool {
    if (opt.obj_dir.empty()) return true;
    const std::string path = opt.obj_dir + "/" + std::to_string(sim.step_count) + ".obj";
    if (auto e = write_file_atomically(path, obj_text(sim)); !e.empty()) {
      std::fprintf(stderr, "invfree: %s\n", e.c_str());
      return false;
    }
    return true;
  };
  if (!write_obj()) return exit_code::kOutputFailed;

  std::ostringstream csv;
  csv.precision(10);
  csv << "step,t,newton_iters,residual,energy,min_det_F,max_det_F,min_gap,ceiling_y,wall_ms\n";
  long total_iterations = 0;
  double total_ms = 0.0;
  StepReport failure;
  for (int k = 0; k < opt.steps; ++k) {
    const StepReport r = step(sim);
    if (r.status != StepStatus::Ok) {
      failure = r;
      break;
    }
    total_iterations += r.newton_iterations;
    total_ms += r.wall_ms;
    const auto det = triangle_det_f(sim);
    const auto [lo, hi] = std::minmax_element(det.begin(), det.end());
    const double gap = min_plane_gap(sim);
    csv << sim.step_count << "," << sim.time << "," << r.newton_iterations << "," << r.residual << ","
        << r.energy << "," << *lo << "," << *hi << "," << (std::isfinite(gap) ? gap : -1.0) << ","
        << (sim.scene.has_ceiling ? sim.ceiling_y : 0.0) << "," << r.wall_ms << "\n";
    if (!write_obj()) return exit_code::kOutputFailed;
  }
  if (!opt.csv_path.empty()) {
    if (auto e = write_file_atomically(opt.csv_path, csv.str()); !e.empty()) {
      std::fprintf(stderr, "invfree: %s\n", e.c_str());
      return exit_code::kOutputFailed;
    }
  }
  const long done = sim.step_count;
  const auto det = triangle_det_f(sim);
  const auto [lo, hi] = std::minmax_element(det.begin(), det.end());
  std::printf("%s: %ld steps, t = %.3f s, %.2f Newton iterations/step, %.3f ms/step, det F in [%.4f, %.4f]\n",
              sim.scene.name.c_str(), done, sim.time,
              done ? double(total_iterations) / done : 0.0, done ? total_ms / done : 0.0, *lo, *hi);
  if (failure.status != StepStatus::Ok) {
    std::fprintf(stderr, "invfree: step %ld failed: %s: %s\n", done + 1, step_status_name(failure.status),
                 failure.message.c_str());
    return exit_code::kRunFailed;
  }
  return exit_code::kOk;
}

}  // namespace

void register_simulate_command(CLI::App& app, int& exit_code) {
  auto opt = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand("simulate", "step a scene without drawing; write CSV and OBJ files");
  opt->scene.add_to(cmd);
  cmd->add_option("--steps", opt->steps, "number of time steps")->capture_default_str()->check(CLI::Range(0, 100000000));
  cmd->add_option("--obj", opt->obj_dir, "write DIR/<k>.obj after k steps (k = 0 is the initial mesh)")
      ->type_name("DIR");
  cmd->add_option("--csv", opt->csv_path,
                  "write one row per step: step,t,newton_iters,residual,energy,min_det_F,max_det_F,"
                  "min_gap,ceiling_y,wall_ms")
      ->type_name("FILE");
  cmd->callback([opt, &exit_code] { exit_code = run_simulate(*opt); });
}

}  // namespace invfree
