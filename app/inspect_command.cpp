// `invfree inspect`: one triangle's stress and stress derivative at a step (issue 26).
// Steps the scene with the same `step` loop as `simulate` (nothing else per step, so it is
// never slower), then lays open the lecture's quantities for one triangle
// (material/stress_analysis.h): as one JSON object (--json) or as a table for a person.
// The triangle is given by index or as the one under a point of the deformed body.
// Mass-spring scenes have no strain energy per triangle: their triangle's geometry (F, its
// polar SVD, J) is reported, the stress quantities are n/a (JSON null).
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/output_files.h"
#include "app/scene_options.h"
#include "material/models.h"
#include "material/stress_analysis.h"
#include "simulation.h"
#include "triangle_fields.h"

namespace invfree {

namespace {

struct InspectOptions {
  SceneOptions scene;
  long step = 0;
  long triangle = -1;
  std::string at;
  bool json = false;
  // Which of --triangle and --at was given (exactly one must be).
  CLI::Option* triangle_option = nullptr;
  CLI::Option* at_option = nullptr;
};

// What is reported: the analysis, and whether the scene has a strain energy at all.
struct Report {
  std::string scene;
  long step = 0;
  double time = 0.0;
  int triangle = 0;
  int triangle_count = 0;
  bool elastic = true;  // false: mass-spring, the stress quantities are n/a
  StressAnalysis a;
  FiniteDifferenceErrors fd;
  // The stress quantities exist: an elastic scene, and Psi finite at F (a neo-Hookean
  // triangle at J <= 0 cannot be reached by a step that succeeded, but is guarded).
  bool has_stress() const { return elastic && a.finite; }
};

// "X,Y": two finite numbers. Empty optional on anything else.
std::optional<Vec2> parse_point(const std::string& text) {
  const size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) return {};
  double v[2];
  const std::string parts[2] = {text.substr(0, comma), text.substr(comma + 1)};
  for (int i = 0; i < 2; ++i) {
    const char* s = parts[i].c_str();
    char* end = nullptr;
    v[i] = std::strtod(s, &end);
    if (parts[i].empty() || *end != '\0' || std::isspace(static_cast<unsigned char>(*s)) ||
        !std::isfinite(v[i]))
      return {};
  }
  return Vec2(v[0], v[1]);
}

// --step: a whole number from 0 to 100000000 (CLI::Range alone would call 1.5 "not in
// range", and "1e3" or "+5" are no step numbers a person writes).
CLI::Validator step_number() {
  return CLI::Validator(
      [](const std::string& value) {
        const bool digits = !value.empty() && value.size() <= 9 &&
                            value.find_first_not_of("0123456789") == std::string::npos;
        if (digits && std::stol(value) <= 100000000L) return std::string();
        return "expected a whole number of steps from 0 to 100000000, got " + value;
      },
      "");
}

// --- JSON -----------------------------------------------------------------------------

// The shortest text that reads back as the same double; null where not finite (JSON has
// no NaN or infinity).
std::string json_number(double x) {
  if (!std::isfinite(x)) return "null";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

std::string json_vec(const double* v, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? ", " : "") + json_number(v[i]);
  return s + "]";
}

// Row-major: [[m11, m12], [m21, m22]].
std::string json_matrix(const Mat2& m) {
  const double r0[2] = {m(0, 0), m(0, 1)}, r1[2] = {m(1, 0), m(1, 1)};
  return "[" + json_vec(r0, 2) + ", " + json_vec(r1, 2) + "]";
}

void print_json(const Report& r) {
  const StressAnalysis& a = r.a;
  const bool s = r.has_stress();
  const auto stress = [s](const std::string& value) { return s ? value : std::string("null"); };
  const double sigma[2] = {a.svd.sigma(0), a.svd.sigma(1)};
  const Vec2 d0 = a.principal_directions.col(0), d1 = a.principal_directions.col(1);
  const std::string principal = "{\"values\": " + json_vec(a.principal_stress.data(), 2) +
                                ", \"directions\": [" + json_vec(d0.data(), 2) + ", " +
                                json_vec(d1.data(), 2) + "]}";
  std::string o = "{\n";
  const auto key = [&o](const char* name, const std::string& value, bool last = false) {
    o += std::string("  \"") + name + "\": " + value + (last ? "\n" : ",\n");
  };
  key("triangle", std::to_string(r.triangle));
  key("model", r.elastic ? "\"" + std::string(model_name(a.model)) + "\"" : "\"mass-spring\"");
  key("mu", r.elastic ? json_number(a.lame.mu) : "null");
  key("lambda", r.elastic ? json_number(a.lame.lambda) : "null");
  key("F", json_matrix(a.F));
  key("U", json_matrix(a.svd.U));
  key("sigma", json_vec(sigma, 2));
  key("V", json_matrix(a.svd.V));
  key("J", json_number(a.J));
  key("psi", stress(json_number(a.psi)));
  key("P", stress(json_matrix(a.P)));
  key("cauchy", stress(json_matrix(a.cauchy)));
  key("principal_stress", stress(principal));
  key("eigenvalues", stress(json_vec(a.eigenvalues.data(), 4)));
  key("projected_eigenvalues", stress(json_vec(a.projected_eigenvalues.data(), 4)));
  key("clamped", stress(std::to_string(a.clamped)));
  key("fd_error_P", stress(json_number(r.fd.P)));
  key("fd_error_dPdF", stress(json_number(r.fd.dPdF)), true);
  o += "}\n";
  std::fputs(o.c_str(), stdout);
}

// --- The table for a person -----------------------------------------------------------------

std::string num(double x) {
  if (!std::isfinite(x)) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// A number right-aligned in a column of `width`.
std::string cell(double x, int width = 13) {
  std::string s = num(x);
  return s.size() < static_cast<size_t>(width) ? std::string(width - s.size(), ' ') + s : s;
}

void row(const std::string& label, const std::string& value, const std::string& note = "") {
  std::printf("%-22s %s%s%s\n", label.c_str(), value.c_str(), note.empty() ? "" : "   ",
              note.c_str());
}

void matrix_rows(const std::string& label, const Mat2& m, const std::string& unit,
                 const std::string& note) {
  const std::string u = unit.empty() ? "" : " " + unit;
  row(label, "[" + cell(m(0, 0)) + cell(m(0, 1)) + " ]" + u, note);
  row("", "[" + cell(m(1, 0)) + cell(m(1, 1)) + " ]" + u);
}

void print_table(const Report& r) {
  const StressAnalysis& a = r.a;
  const bool s = r.has_stress();
  std::printf("%s at step %ld (t = %s s), triangle %d of %d\n", r.scene.c_str(), r.step,
              num(r.time).c_str(), r.triangle, r.triangle_count);
  if (r.elastic)
    row("model", model_label(a.model),
        "mu = " + num(a.lame.mu) + " Pa, lambda = " + num(a.lame.lambda) + " Pa");
  else
    row("model", "mass-spring",
        "springs, no strain energy per triangle: the stress quantities are n/a");
  matrix_rows("F", a.F, "", "deformation gradient (dimensionless)");
  matrix_rows("U", a.svd.U, "", "polar SVD F = U diag(sigma) V^T: U, V rotations");
  row("sigma", cell(a.svd.sigma(0)) + cell(a.svd.sigma(1)),
      "singular values (sigma 2 < 0: inverted)");
  matrix_rows("V", a.svd.V, "", "");
  row("J", num(a.J), "det F: area now / area at rest");
  if (!s) {
    const char* why = r.elastic ? "n/a (psi is +inf: the triangle is inverted)" : "n/a";
    for (const char* key : {"psi", "P", "cauchy", "principal_stress", "eigenvalues",
                            "projected_eigenvalues", "clamped", "fd_error_P", "fd_error_dPdF"})
      row(key, why);
    return;
  }
  row("psi", num(a.psi) + " Pa", "energy density (J/m^3)");
  matrix_rows("P", a.P, "Pa", "first Piola-Kirchhoff stress dPsi/dF");
  matrix_rows("cauchy", a.cauchy, "Pa", "Cauchy stress P F^T / J");
  for (int k = 0; k < 2; ++k)
    row(k == 0 ? "principal_stress" : "",
        cell(a.principal_stress(k)) + " Pa along (" + num(a.principal_directions(0, k)) + ", " +
            num(a.principal_directions(1, k)) + ")",
        k == 0 ? "tension > 0" : "");
  for (int k = 0; k < 4; ++k) {
    const bool clamped = a.eigenvalues(k) < 0.0;
    row(k == 0   ? "eigenvalues"
        : k == 1 ? "  of dP/dF"
                 : "",
        std::string(kEigenvalueNames[static_cast<size_t>(k)]) +
            std::string(8 - std::string(kEigenvalueNames[static_cast<size_t>(k)]).size(), ' ') +
            cell(a.eigenvalues(k)) + " Pa",
        clamped ? "clamped to 0" : "");
  }
  std::string projected;
  for (int k = 0; k < 4; ++k) projected += cell(a.projected_eigenvalues(k));
  row("projected_eigenvalues", projected + " Pa", "after the PSD projection");
  row("clamped", std::to_string(a.clamped) + " of 4", "negative eigenvalues set to 0");
  row("fd_error_P", num(r.fd.P), "relative to central differences of psi");
  row("fd_error_dPdF", num(r.fd.dPdF), "relative to second differences of psi");
}

// --- The command ----------------------------------------------------------------------------

int run_inspect(const InspectOptions& opt) {
  std::string error;
  const auto scene = opt.scene.resolve(&error);
  if (!scene) return fail(exit_code::kBadInput, error);
  const bool by_triangle = opt.triangle_option->count() > 0;
  const bool by_point = opt.at_option->count() > 0;
  if (!by_triangle && !by_point)
    return fail(exit_code::kBadInput, "inspect needs --triangle T or --at X,Y");
  std::optional<Vec2> point;
  if (by_point && !(point = parse_point(opt.at)))
    return fail(exit_code::kBadInput,
                "--at " + opt.at + ": expected X,Y, two numbers in m (e.g. --at -0.1,0.2)");

  Simulation sim = make_simulation(*scene);
  const int count = sim.mesh.triangle_count();
  if (count == 0)  // particles only (the course's chapter 0)
    return fail(exit_code::kBadInput, "scene " + sim.scene.name +
                                          " has no triangles (particles and springs only): "
                                          "nothing to inspect");
  if (by_triangle && (opt.triangle < 0 || opt.triangle >= count))
    return fail(exit_code::kBadInput,
                "--triangle " + std::to_string(opt.triangle) + " is out of range: the mesh has " +
                    std::to_string(count) + " triangles (0 to " + std::to_string(count - 1) + ")");

  // The same stepping as `simulate`, and nothing else per step.
  while (sim.step_count < opt.step) {
    if (interrupted())
      return fail(interrupted_exit_code(),
                  "interrupted after step " + std::to_string(sim.step_count));
    const StepReport r = step(sim);
    if (r.status != StepStatus::Ok) {
      char t[32];
      std::snprintf(t, sizeof t, "%.4g", sim.time + sim.scene.h);
      return fail(exit_code::kRunFailed, "step " + std::to_string(sim.step_count + 1) +
                                             " failed: " + step_status_name(r.status) + ": " +
                                             r.message + " (t = " + t + " s); step " +
                                             std::to_string(opt.step) + " cannot be inspected");
    }
  }

  Report r;
  r.scene = sim.scene.name;
  r.step = sim.step_count;
  r.time = sim.time;
  r.triangle_count = count;
  if (by_point) {
    const std::optional<int> t = triangle_at(sim, *point);
    if (!t)
      return fail(exit_code::kBadInput, "no triangle contains the point (" + num((*point)(0)) +
                                            ", " + num((*point)(1)) + ") at step " +
                                            std::to_string(opt.step));
    r.triangle = *t;
  } else {
    r.triangle = static_cast<int>(opt.triangle);
  }
  r.elastic = sim.scene.has_triangle_elasticity();
  if (r.elastic) {
    r.a = analyze_triangle(sim, r.triangle);
    r.fd = finite_difference_errors(r.a.model, r.a.F, r.a.lame);
  } else {
    // Geometry only: analyze_stress's F, polar SVD and J (its stress numbers are not shown).
    r.a = analyze_stress(sim.scene.model, triangle_deformation_gradient(sim, r.triangle), Lame{});
  }
  if (opt.json)
    print_json(r);
  else
    print_table(r);
  flush_standard_output();
  return exit_code::kOk;
}

}  // namespace

void register_inspect_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<InspectOptions>(
      app, exit_code, "inspect",
      "step a scene to a step and show one triangle's F, polar SVD, stress and the "
      "eigenvalues of dP/dF (the lecture's quantities)",
      run_inspect);
  opt.scene.add_to(cmd);
  cmd->add_option("--step", opt.step,
                  "the step to inspect: the state after N steps (0 to "
                  "100000000; 0: the initial state)")
      ->required()
      ->type_name("N")
      ->check(step_number());
  opt.triangle_option =
      cmd->add_option("--triangle", opt.triangle, "the triangle's index (0 to triangles - 1)")
          ->type_name("T");
  opt.at_option = cmd->add_option("--at", opt.at,
                                  "the triangle containing the point X,Y (m) of the deformed "
                                  "body, e.g. --at -0.1,0.2")
                      ->type_name("X,Y");
  opt.triangle_option->excludes(opt.at_option);
  cmd->add_flag("--json", opt.json,
                "print one JSON object (keys in docs/cli.md) instead of a table");
}

}  // namespace invfree
