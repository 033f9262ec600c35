// `invfree landscape`: the energy landscape Psi(sigma1, sigma2) of a model (issue 26, the
// lecture's "Psi in the diagonal space"), as a chart (app/landscape/landscape_chart.h):
//   invfree landscape --model M|all [--scene S [--set ...] [--step N]] [--mu X --lambda Y]
//                     --out FILE.png|svg|pdf [--format F] [--force]
// `--model all` puts the four models side by side on one colour scale. With --scene the
// scene's Lame parameters are used and every triangle's (sigma1, sigma2) after step N is a
// dot (exit 3 when a step before it fails). Bad input: one line, exit 2.
#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "app/cli_checks.h"
#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/format_number.h"
#include "app/interrupt.h"
#include "app/landscape/landscape_chart.h"
#include "app/output_files.h"
#include "app/scene_options.h"
#include "material/models.h"
#include "simulation.h"

namespace invfree {

namespace {

struct LandscapeOptions {
  std::string model;  // a model's name, or "all"; empty: the scene's
  SceneOptions scene;
  int step = 0;
  double mu = 0.0, lambda = 0.0;
  std::string out;
  std::string format;  // empty: from the extension of --out
  bool force = false;
  // Which options the command line gave (the defaults alone cannot tell).
  CLI::Option *scene_opt = nullptr, *set_opt = nullptr, *step_opt = nullptr, *mu_opt = nullptr,
              *lambda_opt = nullptr, *model_opt = nullptr;
};

std::string extension_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return std::tolower(ch); });
  return ext;
}

std::string step_failure_message(const Simulation& sim, const StepReport& failure) {
  char t[32];
  std::snprintf(t, sizeof t, "%.4g", sim.time + sim.scene.h);
  return "step " + std::to_string(sim.step_count + 1) +
         " failed: " + step_status_name(failure.status) + ": " + failure.message + " (t = " + t +
         " s); no landscape written";
}

std::string model_choices() {
  std::string s;
  for (const auto& m : model_names()) s += std::string(m.name) + ", ";
  return s + "all";
}

int run_landscape(const LandscapeOptions& opt) {
  const bool with_scene = opt.scene_opt->count() > 0;
  if (!with_scene && opt.set_opt->count() > 0)
    return fail(exit_code::kBadInput, "--set changes a scene: give --scene too");
  if (!with_scene && opt.step_opt->count() > 0)
    return fail(exit_code::kBadInput, "--step is a step of a scene: give --scene too");
  if (with_scene && (opt.mu_opt->count() > 0 || opt.lambda_opt->count() > 0))
    return fail(exit_code::kBadInput,
                "--mu and --lambda are for a landscape without a scene; with --scene use --set "
                "material.mu=... --set material.lambda=...");
  if (!with_scene && opt.model_opt->count() == 0)
    return fail(exit_code::kBadInput,
                "--model is required without --scene (" + model_choices() + ")");

  // The models drawn.
  std::vector<Model> models;
  if (opt.model == "all") {
    for (const auto& m : model_names()) models.push_back(m.value);
  } else if (!opt.model.empty()) {
    const auto m = model_from_name(opt.model);
    if (!m)
      return fail(exit_code::kBadInput,
                  "unknown --model " + opt.model + " (choose one of " + model_choices() + ")");
    models.push_back(*m);
  }

  // The file format: --format, or the extension of --out; they must agree.
  const std::string ext = extension_of(opt.out);
  const auto ext_format = parse_chart_format(ext);
  std::optional<ChartFormat> format;
  if (!opt.format.empty()) {
    format = parse_chart_format(opt.format);
    if (!format)
      return fail(exit_code::kBadInput, "unknown --format " + opt.format + " (png, svg or pdf)");
    if (ext_format != format)
      return fail(exit_code::kBadInput, "--out " + opt.out + " does not end in ." +
                                            chart_extension(*format) + " (--format " + opt.format +
                                            ")");
  } else {
    format = ext_format;
    if (!format)
      return fail(exit_code::kBadInput,
                  "--out " + opt.out + " must end in .png, .svg or .pdf (the chart's format)");
  }

  LandscapeChartSpec spec;
  std::optional<SceneDef> scene;
  if (with_scene) {
    std::string error;
    scene = opt.scene.resolve(&error);
    if (!scene) return fail(exit_code::kBadInput, error);
    if (models.empty()) models.push_back(scene->model);
    spec.lame = scene->lame;
  } else {
    spec.lame = lame_from_young_poisson(1e5, 0.4);  // the scenes' default material
    if (opt.mu_opt->count() > 0) spec.lame.mu = opt.mu;
    if (opt.lambda_opt->count() > 0) spec.lame.lambda = opt.lambda;
    if (!(spec.lame.mu > 0.0))
      return fail(exit_code::kBadInput, "--mu must be > 0, got " + format_number(opt.mu, "%g"));
  }
  spec.models = models;

  const std::vector<std::string> inputs =
      with_scene ? opt.scene.input_files() : std::vector<std::string>{};
  if (auto e = check_output_files({opt.out}, inputs, opt.force))
    return fail(e.exit_code, e.message);

  if (scene) {
    Simulation sim = make_simulation(*scene);
    while (sim.step_count < opt.step) {
      if (interrupted())
        return fail(interrupted_exit_code(),
                    "interrupted at step " + std::to_string(sim.step_count) + "; nothing written");
      const StepReport r = step(sim);
      if (r.status != StepStatus::Ok)
        return fail(exit_code::kRunFailed, step_failure_message(sim, r));
    }
    triangle_sigmas(sim, &spec.points);
    char t[32];
    std::snprintf(t, sizeof t, "%.4g", sim.time);
    spec.points_caption = "Dots: the " + format_for_people(double(spec.points.size())) +
                          " triangles of " + scene->name + " (" + model_label(scene->model) +
                          ") at step " + std::to_string(sim.step_count) + ", t = " + t + " s";
    if (spec.points.empty())  // particles only (the course's chapter 0)
      spec.points_caption = scene->name + " has no triangles (particles and springs only): no dots";
    else if (!scene->has_triangle_elasticity())
      spec.notes.push_back(
          "A mass-spring scene: its springs have no \u03a8(F); the dots are its triangles' "
          "singular values, drawn on the landscape of its [material] model for comparison.");
    if (!sim.triangle_lame.empty())
      spec.notes.push_back(
          "The scene's bodies have their own Lam\u00e9 parameters: the landscape is drawn with "
          "the scene's [material]; a dot of another body sits on its own landscape, scaled.");
    const LandscapeDomain d = chart_domain(spec);
    const long outside =
        std::count_if(spec.points.begin(), spec.points.end(), [&](const SigmaPair& p) {
          return !(p.s1 >= d.s1_min && p.s1 <= d.s1_max && p.s2 >= d.s2_min && p.s2 <= d.s2_max);
        });
    if (outside > 0)
      spec.notes.push_back(format_for_people(double(outside)) +
                           " triangles lie beyond the drawn domain (a stretch past 2): "
                           "each is pinned to the domain's edge.");
  }

  if (auto e = write_canvas(opt.out, *landscape_chart(spec, *format)); !e.empty())
    return fail(exit_code::kOutputFailed, e);
  std::string what = models.size() == 1 ? model_label(models[0]) : "4 models";
  std::string dots;  // the scene's triangles, or that it has none (particles only)
  if (!spec.points.empty())
    dots = "; " + format_for_people(double(spec.points.size())) + " triangles at step " +
           std::to_string(opt.step);
  else if (scene)
    dots = "; " + scene->name + " has no triangles (particles only)";
  std::printf("landscape: %s, mu = %s, lambda = %s%s; wrote %s\n", what.c_str(),
              format_pascal(spec.lame.mu).c_str(), format_pascal(spec.lame.lambda).c_str(),
              dots.c_str(), opt.out.c_str());
  flush_standard_output();
  return exit_code::kOk;
}

}  // namespace

void register_landscape_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<LandscapeOptions>(
      app, exit_code, "landscape",
      "chart the energy density psi(sigma1, sigma2) of a model over its singular values, with "
      "a scene's triangles as dots",
      run_landscape);
  opt.model_opt = cmd->add_option("--model", opt.model,
                                  "material model (" + model_choices() +
                                      ": the four side by side); default with --scene: its model")
                      ->type_name("MODEL");
  opt.scene.add_to(cmd, "a scene whose triangles are drawn as dots: built-in scene",
                   "override a scene value");
  // No scene unless one is given: the help shows no default.
  opt.scene_opt = cmd->get_option("--scene")->default_str("");
  opt.set_opt = cmd->get_option("--set");
  opt.step_opt =
      cmd->add_option("--step", opt.step,
                      "the scene's triangles after this many steps (0: the initial state)")
          ->capture_default_str()
          ->check(CLI::Range(0, 100000000));
  opt.mu_opt =
      cmd->add_option("--mu", opt.mu, "Lame mu in Pa without --scene (default: E = 1e5, nu = 0.4)")
          ->check(finite_range(0.0, 1e15));
  opt.lambda_opt = cmd->add_option("--lambda", opt.lambda, "Lame lambda in Pa without --scene")
                       ->check(finite_range(0.0, 1e15));
  cmd->add_option("--out", opt.out, "the chart: FILE.png, FILE.svg or FILE.pdf")
      ->required()
      ->type_name("FILE")
      ->check(non_empty_path());
  cmd->add_option("--format", opt.format, "png, svg or pdf (default: from the extension of --out)");
  add_force_option(cmd, opt.force, "overwrite an existing --out file");
}

}  // namespace invfree
