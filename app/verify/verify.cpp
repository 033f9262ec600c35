#include "app/verify/verify.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "app/format_number.h"
#include "app/plot/loglog_fit.h"
#include "app/verify/reference_solutions.h"
#include "scene_io/did_you_mean.h"

namespace invfree {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool ran(const VerifyRow& r) {
  return r.run.failure.empty() && std::isfinite(r.run.relative_error);
}

// Okabe-Ito, distinguishable with the common colour-vision deficiencies.
Rgb case_color(VerifyCaseKind kind) {
  switch (kind) {
    case VerifyCaseKind::Patch:
      return {0.35f, 0.35f, 0.35f};
    case VerifyCaseKind::Cantilever:
      return {0.00f, 0.45f, 0.70f};
    case VerifyCaseKind::Kirsch:
      return {0.84f, 0.37f, 0.00f};
    case VerifyCaseKind::Cook:
      return {0.00f, 0.62f, 0.45f};
    case VerifyCaseKind::CookIncompressible:
      return {0.90f, 0.62f, 0.00f};
    case VerifyCaseKind::LargeStrain:
      return {0.80f, 0.47f, 0.65f};
  }
  return {0.2f, 0.2f, 0.2f};
}

std::string slope_text(double s) {
  return std::isfinite(s) ? format_number(s, "%.2f") : std::string();
}

// "-1" or "-0.5" as a theoretical order is written.
std::string order_text(double s) {
  return format_number(s, "%g");
}

}  // namespace

std::string parse_verify_cases(const std::string& text, std::vector<const VerifyCase*>& cases) {
  cases.clear();
  if (text.empty() || text == "all") {
    for (const VerifyCase& c : verify_cases()) cases.push_back(&c);
    return "";
  }
  std::vector<std::string> names;
  for (const VerifyCase& c : verify_cases()) names.push_back(c.name);
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const VerifyCase* c = find_verify_case(item);
    if (c == nullptr) {
      std::string shown = item.substr(0, 40);
      for (char& ch : shown)
        if (ch < ' ' || ch == 127) ch = '?';
      return "--cases: unknown case \"" + shown + "\"" + did_you_mean(item, names) +
             " (cases: " + verify_case_names() + ", or all)";
    }
    bool seen = false;
    for (const VerifyCase* d : cases) seen = seen || d == c;
    if (!seen) cases.push_back(c);
  }
  if (cases.empty()) return "--cases: expected a comma-separated list of cases, e.g. patch,cook";
  return "";
}

VerifyResult run_verify(const std::vector<const VerifyCase*>& cases, const SweepOptions& options) {
  VerifyResult result;
  result.cases = cases;
  result.quick = options.quick;
  for (const VerifyCase* c : cases) {
    const std::vector<int>& levels = options.quick ? c->quick_levels : c->levels;
    const VerifyRow* previous = nullptr;
    for (int n : levels) {
      if (options.stop_requested()) {
        result.stopped = true;
        return result;
      }
      VerifyRow row;
      row.case_name = c->name;
      row.n_seg = n;
      row.slope = kNaN;
      std::string error;
      const auto start = std::chrono::steady_clock::now();
      if (auto scene = verify_case_scene(*c, n, &error)) {
        row.run = run_verify_case(*c, *scene);
      } else {
        row.run.computed = row.run.reference = row.run.relative_error = kNaN;
        row.run.failure = error;
      }
      const double wall_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      result.total_wall_s += row.run.solve_ms / 1000.0;
      if (!verify_case_is_exact(*c) && previous != nullptr && ran(*previous) && ran(row) &&
          row.run.unknowns != previous->run.unknowns)
        row.slope = std::log(row.run.relative_error / previous->run.relative_error) /
                    std::log(double(row.run.unknowns) / previous->run.unknowns);
      options.report(c->name + ": n_seg " + std::to_string(n) + ", " +
                     format_for_people(row.run.unknowns) + " unknowns: " +
                     (row.run.failure.empty()
                          ? "relative error " + format_number(row.run.relative_error, "%.3g")
                          : "failed: " + row.run.failure) +
                     " (" + format_number(wall_s, "%.2f") + " s)");
      result.rows.push_back(row);
      previous = &result.rows.back();
    }
  }
  return result;
}

double verify_fitted_slope(const VerifyResult& result, const std::string& case_name) {
  const VerifyCase* c = find_verify_case(case_name);
  if (c == nullptr || verify_case_is_exact(*c)) return kNaN;
  std::vector<double> x, y;
  for (const VerifyRow& r : result.rows)
    if (r.case_name == case_name && ran(r)) {
      x.push_back(r.run.unknowns);
      y.push_back(r.run.relative_error);
    }
  return fit_loglog(x, y).slope;
}

bool verify_failed(const VerifyResult& result) {
  for (const VerifyRow& r : result.rows)
    if (!r.run.failure.empty()) return true;
  return false;
}

std::string verify_csv(const VerifyResult& result) {
  std::ostringstream o;
  o << "case,n_seg,max_edge,unknowns,triangles,computed,reference,relative_error,slope,"
       "load_steps,newton_iterations,solve_ms,failure\n";
  auto num = [](double v, const char* f) {
    return std::isfinite(v) ? format_number(v, f) : std::string();
  };
  for (const VerifyRow& r : result.rows) {
    std::string failure = r.run.failure;
    for (char& ch : failure)
      if (ch == ',' || ch == '\n' || ch == '\r') ch = ';';
    o << r.case_name << "," << r.n_seg << "," << num(r.run.max_edge, "%.6g") << ","
      << r.run.unknowns << "," << r.run.triangles << "," << num(r.run.computed, "%.10g") << ","
      << num(r.run.reference, "%.10g") << "," << num(r.run.relative_error, "%.6g") << ","
      << num(r.slope, "%.4f") << "," << r.run.load_steps << "," << r.run.newton_iterations << ","
      << num(r.run.solve_ms, "%.3f") << "," << failure << "\n";
  }
  return o.str();
}

std::string verify_table(const VerifyResult& result) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-20s %6s %9s %15s %15s %11s %6s\n", "case", "n_seg",
                "unknowns", "computed", "reference", "rel. error", "slope");
  out += line;
  for (const VerifyRow& r : result.rows) {
    if (!r.run.failure.empty()) {
      std::snprintf(line, sizeof line, "%-20s %6d %9d  failed: %s\n", r.case_name.c_str(), r.n_seg,
                    r.run.unknowns, r.run.failure.c_str());
      out += line;
      continue;
    }
    std::snprintf(line, sizeof line, "%-20s %6d %9d %15.9g %15.9g %11.3e %6s\n",
                  r.case_name.c_str(), r.n_seg, r.run.unknowns, r.run.computed, r.run.reference,
                  r.run.relative_error, slope_text(r.slope).c_str());
    out += line;
  }
  for (const VerifyCase* c : result.cases) {
    double worst = 0.0;
    bool any = false;
    for (const VerifyRow& r : result.rows)
      if (r.case_name == c->name && ran(r)) {
        worst = std::max(worst, r.run.relative_error);
        any = true;
      }
    if (!any) continue;
    if (verify_case_is_exact(*c)) {
      std::snprintf(line, sizeof line, "%s: exact on every mesh, largest error %.2e\n",
                    c->name.c_str(), worst);
    } else {
      std::snprintf(line, sizeof line, "%s: fitted slope %s (theory %s)\n", c->name.c_str(),
                    slope_text(verify_fitted_slope(result, c->name)).c_str(),
                    order_text(c->expected_slope).c_str());
    }
    out += line;
  }
  return out;
}

namespace {

// A dashed guide of slope `slope` across [x0, x1] through (x0, y0).
Series guide(double slope, double x0, double x1, double y0, double dash, float grey,
             const std::string& label) {
  Series g;
  g.label = label;
  g.color = {grey, grey, grey};
  g.markers = false;
  g.dash = dash;
  g.x = {x0, x1};
  g.y = {y0, y0 * std::pow(x1 / x0, slope)};
  return g;
}

// One series per case of `exact` kind (the convergent cases, or the exact ones).
std::vector<Series> case_series(const VerifyResult& result, bool exact) {
  std::vector<Series> series;
  for (const VerifyCase* vc : result.cases) {
    if (verify_case_is_exact(*vc) != exact) continue;
    Series s;
    s.color = case_color(vc->kind);
    for (const VerifyRow& r : result.rows)
      if (r.case_name == vc->name && ran(r)) {
        s.x.push_back(r.run.unknowns);
        // An error of exactly 0 would vanish from a log axis: drawn at 1e-17 (rounding).
        s.y.push_back(std::max(r.run.relative_error, 1e-17));
      }
    s.label = exact ? vc->label
                    : vc->label + ", slope " + slope_text(verify_fitted_slope(result, vc->name)) +
                          " (theory " + order_text(vc->expected_slope) + ")";
    series.push_back(s);
  }
  return series;
}

ChartSpec convergence_panel(const VerifyResult& result) {
  ChartSpec c;
  c.title = std::string("Convergence under mesh refinement") + (result.quick ? " (--quick)" : "") +
            ": relative error against unknowns";
  c.x_label = "unknowns (free degrees of freedom)";
  c.y_label = "relative error";
  c.log_x = c.log_y = true;
  c.series = case_series(result, false);
  // A guide per theoretical slope, across the whole range of unknowns and below every
  // point (half as far as the closest one), so that it crosses no case's line.
  double x_lo = INFINITY, x_hi = 0.0;
  std::vector<const VerifyRow*> points;
  std::vector<double> slopes;
  for (const VerifyRow& r : result.rows) {
    const VerifyCase* vc = find_verify_case(r.case_name);
    if (vc == nullptr || verify_case_is_exact(*vc) || !ran(r) || !(r.run.relative_error > 0.0))
      continue;
    x_lo = std::min(x_lo, double(r.run.unknowns));
    x_hi = std::max(x_hi, double(r.run.unknowns));
    points.push_back(&r);
    if (std::find(slopes.begin(), slopes.end(), vc->expected_slope) == slopes.end())
      slopes.push_back(vc->expected_slope);
  }
  std::sort(slopes.begin(), slopes.end());
  if (x_hi > x_lo)
    for (double slope : slopes) {
      double k = INFINITY;  // min over the points of error / N^slope
      for (const VerifyRow* r : points)
        k = std::min(k, r->run.relative_error / std::pow(double(r->run.unknowns), slope));
      c.series.push_back(guide(slope, x_lo, x_hi, 0.5 * k * std::pow(x_lo, slope),
                               slope == -1.0 ? 11.0 : 4.0, slope == -1.0 ? 0.30f : 0.60f,
                               "guide: slope " + order_text(slope) +
                                   (slope == -1.0 ? " (error ~ h\u00b2)" : " (error ~ h)")));
    }
  c.notes.push_back(
      "Each point is one mesh, n_seg doubling from point to point (max_edge = the longer side "
      "/ n_seg); the slopes are least-squares fits of log(error) against log(unknowns) over "
      "every mesh. Linear triangles' displacements converge as h\u00b2 (slope -1 against "
      "unknowns), a stress recovered at a node as h (slope -0.5). Nearly incompressible Cook's "
      "membrane locks and converges only as h (docs/verification.md).");
  return c;
}

ChartSpec exact_panel(const VerifyResult& result) {
  ChartSpec c;
  c.title = "Exact on every mesh: the error is rounding (and Newton's tolerance)";
  c.x_label = "unknowns (free degrees of freedom)";
  c.y_label = "relative error";
  c.log_x = c.log_y = true;
  c.series = case_series(result, true);
  c.notes.push_back(
      "Patch test: an irregular mesh, the boundary held at F* = diag(1.2, 0.9), the interior "
      "jittered; every triangle's F must come back to F*. Large strain: every triangle's "
      "stretches against the closed form at every load step (below).");
  return c;
}

ChartSpec large_strain_panel(const VerifyResult& result) {
  ChartSpec c;
  c.title = "Large strain: plane-strain uniaxial tension, nominal stress against stretch";
  c.x_label = "stretch along the load (F11)";
  c.y_label = "nominal stress P11 (Pa)";
  const VerifyRow* finest = nullptr;
  for (const VerifyRow& r : result.rows)
    if (r.case_name == "large-strain" && ran(r)) finest = &r;
  if (finest == nullptr) return c;
  std::string error;
  const auto scene = verify_case_scene(*find_verify_case("large-strain"), finest->n_seg, &error);
  if (!scene) return c;
  const double mu = scene->lame.mu, lambda = scene->lame.lambda;
  double a_max = 1.0;
  for (const LoadPathPoint& p : finest->run.path) a_max = std::max(a_max, p.stretch);
  a_max *= 1.05;
  Series exact, linear, computed;
  exact.label = "neo-Hookean, closed form";
  exact.color = {0.0f, 0.0f, 0.0f};
  exact.markers = false;
  linear.label = "small-strain line E' (F11 - 1)";
  linear.color = {0.55f, 0.55f, 0.55f};
  linear.markers = false;
  linear.dash = 7.0;
  const double e_prime = plane_strain_uniaxial_modulus(mu, lambda);
  for (int k = 0; k <= 100; ++k) {
    const double a = 1.0 + (a_max - 1.0) * k / 100.0;
    exact.x.push_back(a);
    exact.y.push_back(uniaxial_nominal_stress(a, mu, lambda));
  }
  double p_max = exact.y.back();
  linear.x = {1.0, 1.0 + p_max / e_prime};
  linear.y = {0.0, p_max};
  computed.label =
      "invfree, each load step (" + format_for_people(finest->run.triangles) + " triangles)";
  computed.color = case_color(VerifyCaseKind::LargeStrain);
  computed.lines = false;
  computed.x.push_back(1.0);
  computed.y.push_back(0.0);
  for (const LoadPathPoint& p : finest->run.path) {
    computed.x.push_back(p.stretch);
    computed.y.push_back(p.nominal_stress);
  }
  c.series = {exact, linear, computed};
  double E, nu;
  young_poisson_from_lame(scene->lame, &E, &nu);
  c.notes.push_back(
      "A strip pulled by a dead load on its end in " + std::to_string(finest->run.load_steps) +
      " equal load steps (E = " + format_number(E, "%g") + " Pa, nu = " + format_number(nu, "%g") +
      ", plane strain); every triangle's stretch "
      "matches the closed form to " +
      format_number(finest->run.relative_error, "%.1e") + " (relative) at every step.");
  return c;
}

}  // namespace

std::vector<ChartSpec> verify_panels(const VerifyResult& result) {
  std::vector<ChartSpec> panels;
  bool rates = false, exact = false;
  for (const VerifyCase* c : result.cases) (verify_case_is_exact(*c) ? exact : rates) = true;
  if (rates || !exact) panels.push_back(convergence_panel(result));
  if (exact) panels.push_back(exact_panel(result));
  for (const VerifyRow& r : result.rows)
    if (r.case_name == "large-strain" && ran(r)) {
      panels.push_back(large_strain_panel(result));
      break;
    }
  return panels;
}

}  // namespace invfree
