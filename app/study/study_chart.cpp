#include "app/study/study_chart.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

#include "app/format_number.h"
#include "app/study/methods.h"
#include "scene/scene_mesh.h"

namespace invfree {

namespace {

std::string join_times(const std::vector<double>& t) {
  std::string s;
  for (size_t i = 0; i < t.size(); ++i) s += (i ? ", " : "") + format_number(t[i], "%.4g");
  return s;
}

bool ran(const StudyResult& r, const Method& m) {
  return study_ran_method(r, m.name);
}

// "neo-hookean (slope -0.04), linear (slope 0.02)": the models whose errors do not fall
// with h.
std::string non_converging_list(const StudyResult& r) {
  std::string s;
  for (const ModelConvergence* c : non_converging_models(r))
    s += (s.empty() ? "" : ", ") + c->model + " (slope " + format_number(c->slope, "%.2f") + ")";
  return s;
}

// Failed runs are not plotted; they are listed per method in the notes.
void add_failure_notes(const StudyResult& r, bool (*in_sweep)(const StudyResult&, const StudyRow&),
                       const char* key, std::vector<std::string>& notes) {
  std::map<std::string, std::string> by_method;
  for (const StudyRow& row : r.rows) {
    if (!in_sweep(r, row) || row.failure == "ok") continue;
    std::string& s = by_method[row.method];
    const double v = std::string(key) == "h" ? row.h : row.tol;
    s += (s.empty() ? "" : ", ") + std::string(key) + " = " + format_number(v, "%.4g") + " " +
         row.failure;
  }
  for (const auto& [method, s] : by_method) notes.push_back(method + " failed: " + s);
}

// The rows of `method` in a sweep that have an error to plot (failed runs have none;
// they are listed in the notes).
std::vector<const StudyRow*> plotted_rows(const StudyResult& r, const std::string& method,
                                          bool (*in_sweep)(const StudyResult&, const StudyRow&)) {
  std::vector<const StudyRow*> rows;
  for (const StudyRow& row : r.rows)
    if (row.method == method && in_sweep(r, row) && std::isfinite(row.error) && row.error > 0.0)
      rows.push_back(&row);
  return rows;
}

// One series per study method (its label and colour): error against row.*x over the h sweep.
std::vector<Series> h_sweep_series(const StudyResult& r, double StudyRow::*x) {
  std::vector<Series> series;
  for (const Method& m : study_methods()) {
    if (!ran(r, m)) continue;
    Series s;
    s.label = m.label;
    s.color = method_color(m.name);
    for (const StudyRow* row : plotted_rows(r, m.name, in_h_sweep)) {
      s.x.push_back(row->*x);
      s.y.push_back(row->error);
    }
    series.push_back(s);
  }
  return series;
}

}  // namespace

Rgb method_color(const std::string& method) {
  // Okabe-Ito, distinguishable with the common colour-vision deficiencies.
  static const std::map<std::string, Rgb> colors = {{"lecture", {0.00f, 0.45f, 0.70f}},
                                                    {"full-eigen-clamp", {0.90f, 0.62f, 0.00f}},
                                                    {"no-projection", {0.84f, 0.37f, 0.00f}},
                                                    {"no-inversion-filter", {0.80f, 0.47f, 0.65f}},
                                                    {"symplectic-euler", {0.34f, 0.71f, 0.91f}},
                                                    {"linear", {0.00f, 0.62f, 0.45f}},
                                                    {"arap", {0.55f, 0.34f, 0.16f}},
                                                    {"stable-neo-hookean", {0.55f, 0.55f, 0.55f}},
                                                    {"lecture-mesh", {0.00f, 0.45f, 0.70f}}};
  auto it = colors.find(method);
  return it == colors.end() ? Rgb{0.2f, 0.2f, 0.2f} : it->second;
}

std::vector<size_t> pareto_front(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<size_t> idx;
  for (size_t i = 0; i < std::min(x.size(), y.size()); ++i)
    if (std::isfinite(x[i]) && std::isfinite(y[i])) idx.push_back(i);
  std::sort(idx.begin(), idx.end(),
            [&](size_t a, size_t b) { return x[a] < x[b] || (x[a] == x[b] && y[a] < y[b]); });
  std::vector<size_t> front;
  double best = INFINITY;
  for (size_t i : idx)
    if (y[i] < best) {
      front.push_back(i);
      best = y[i];
    }
  return front;
}

namespace {

// Why a model without convergence has no front (the first note of both study.png panels).
std::string non_converging_note(const StudyResult& r) {
  std::string s;
  for (const ModelConvergence* c : non_converging_models(r))
    s += (s.empty() ? "" : "; ") + c->model + ": errors " + format_number(c->error_lo, "%.2g") +
         " ... " + format_number(c->error_hi, "%.2g") + ", fitted slope " +
         format_number(c->slope, "%.2f");
  return "Errors that do not fall with h, or never come within " +
         format_number(100 * kMaxConvergedError, "%.0f") + "% of the side (" + s +
         "; converging errors fall at a slope of at least " +
         format_number(kMinConvergenceSlope, "%.1f") +
         "), measure how far each run drifts from the reference - contact events out of phase, "
         "bodies taking other paths - not how accurately a method solves; they rank nothing, so "
         "no Pareto front is drawn for these models.";
}

// The error axis: relative to the square's side, or to a meshed shape's longer side.
std::string error_label(const StudyResult& r) {
  return scene_has_only_squares(r.scene) ? "RMS node-position error / side length"
                                         : "RMS node-position error / body size";
}

// Error against wall time over the h sweep, with the Pareto front.
ChartSpec speed_accuracy_panel(const StudyResult& r) {
  const std::string scene = r.scene.name;
  ChartSpec a;
  // A meshed shape (issue 27) has no n_seg x n_seg grid: its n_seg sets max_edge, and the
  // error is relative to its longer side (app/body_extent.h's scene_length_scale).
  const bool squares = scene_has_only_squares(r.scene);
  const std::string n = std::to_string(r.scene.n_seg);
  a.title = "Speed against accuracy: " + scene + " (" +
            (squares ? n + "x" + n + " mesh" : "n_seg " + n + " meshed shape") +
            "), each point one time step h";
  a.x_label = "wall-clock time per simulated second (s/s)";
  a.y_label = error_label(r);
  a.log_x = a.log_y = true;
  a.series = h_sweep_series(r, &StudyRow::wall_s);
  // One Pareto front per material model: a model's errors are measured against its own
  // reference, so a point of one model cannot beat a point of another.
  std::vector<std::string> models;
  for (const Method& m : study_methods())
    if (ran(r, m) && std::find(models.begin(), models.end(), method_model(m)) == models.end())
      models.push_back(method_model(m));
  for (const std::string& model : models) {
    // Errors that do not fall with h rank nothing: no front (the title says why).
    if (const ModelConvergence* c = model_convergence(r, model); c && c->judged && !c->converges)
      continue;
    std::vector<double> xs, ys, hs;
    int methods = 0;
    std::string member;
    for (const Method& m : study_methods()) {
      if (!ran(r, m) || method_model(m) != model) continue;
      ++methods;
      member = m.name;
      for (const StudyRow* row : plotted_rows(r, m.name, in_h_sweep)) {
        xs.push_back(row->wall_s);
        ys.push_back(row->error);
        hs.push_back(row->h);
      }
    }
    Series front;
    front.label = "Pareto front, " + model +
                  (methods > 1 ? " (" + std::to_string(methods) + " methods, one reference)"
                               : " (its own reference)");
    front.color = methods > 1 ? Rgb{0.0f, 0.0f, 0.0f} : method_color(member);
    front.markers = false;
    front.dash = 9.0;
    for (size_t i : pareto_front(xs, ys)) {
      front.x.push_back(xs[i]);
      front.y.push_back(ys[i]);
      front.point_labels.push_back("h = " + format_number(hs[i], "%.3g"));
    }
    if (!front.x.empty()) a.series.push_back(front);
  }
  double h_lo = INFINITY, h_hi = 0.0, e_lo = INFINITY, e_hi = 0.0;
  for (const StudyRow& row : r.rows) {
    if (!in_h_sweep(r, row) || !find_method(row.method)) continue;
    double& lo = find_method(row.method)->implicit() ? h_lo : e_lo;
    double& hi = find_method(row.method)->implicit() ? h_hi : e_hi;
    lo = std::min(lo, row.h);
    hi = std::max(hi, row.h);
  }
  a.notes.push_back(
      "Each model is measured against its own reference, so errors compare only within a "
      "model: the dashed lines are one Pareto front per model (nothing of that model is both "
      "faster and more accurate), their points labelled with h.");
  a.notes.push_back(
      "Error at t = " + join_times(r.sample_times) +
      " s against a reference of the same model at h = " + format_number(r.reference_h) +
      " s, tol = " + format_number(r.reference_tol) +
      " m/s. Implicit methods: h = " + format_number(h_hi) + " ... " + format_number(h_lo) +
      " s; symplectic Euler: h = " + format_number(e_hi) + " ... " + format_number(e_lo) + " s.");
  add_failure_notes(r, in_h_sweep, "h", a.notes);
  for (const std::string& f : r.reference_failures) a.notes.push_back(f);
  if (const std::string list = non_converging_list(r); !list.empty()) {
    a.title = "ERRORS DO NOT CONVERGE WITH h, no Pareto front for " + list + ": " + a.title;
    a.notes.insert(a.notes.begin(), non_converging_note(r));
  }
  return a;
}

// Error against h: every method on the scene, the classic check without contact, and a
// first-order guide.
ChartSpec convergence_panel(const StudyResult& r) {
  ChartSpec b;
  b.title = "Convergence: implicit Euler without contact, fitted slope " +
            format_number(r.smooth_slope, "%.2f") + " (first order = 1); with contact " +
            format_number(r.lecture_slope, "%.2f");
  b.x_label = "time step h (s)";
  b.y_label = error_label(r);
  b.log_x = b.log_y = true;
  double h_min = INFINITY, h_max = 0.0, e_at_min = NAN;
  b.series = h_sweep_series(r, &StudyRow::h);
  {
    Series s;
    s.label = "classic check: lecture's method, same scene without ground and ceiling";
    s.color = {0.0f, 0.0f, 0.0f};
    for (const StudyRow& row : r.rows)
      if (row.method == "lecture-no-contact" && std::isfinite(row.error) && row.error > 0.0) {
        s.x.push_back(row.h);
        s.y.push_back(row.error);
        h_max = std::max(h_max, row.h);
        if (row.h < h_min) {
          h_min = row.h;
          e_at_min = row.error;
        }
      }
    b.series.push_back(s);
  }
  if (std::isfinite(e_at_min)) {
    Series guide;
    guide.label = "slope 1 (first order)";
    guide.color = {0.45f, 0.45f, 0.45f};
    guide.markers = false;
    // Through the check's smallest-h point, offset below it so both stay visible.
    for (double f : {1.0, h_max / h_min}) {
      guide.x.push_back(h_min * f);
      guide.y.push_back(0.5 * e_at_min * f);
    }
    b.series.push_back(guide);
  }
  if (const std::string list = non_converging_list(r); !list.empty()) {
    b.title = "ERRORS DO NOT CONVERGE WITH h: " + list + "; " + b.title;
    b.notes.push_back(non_converging_note(r));
  }
  b.notes.push_back(
      "Fitted slopes of log(error) against log(h), lecture's method over all its h: " +
      format_number(r.smooth_slope, "%.3f") +
      " without contact (each against its own reference), " +
      format_number(r.lecture_slope, "%.3f") + " on the scene itself (" +
      format_number(r.lecture_slope_small_h, "%.2f") + " over its four smallest h).");
  b.notes.push_back(
      "With contact, the barrier's stiff response at impact (a time scale of about a millisecond) "
      "and the numerical damping of the vibrations it starts dominate the error at these h; "
      "first order returns only for h well below that time scale.");
  b.notes.push_back(
      "The neo-Hookean implicit variants share one minimiser per step, so their errors coincide; "
      "they differ in cost and in where they fail.");
  return b;
}

// Error against wall time over the Newton tolerance sweep of every implicit method.
ChartSpec tolerance_panel(const StudyResult& r) {
  ChartSpec c;
  c.title =
      "Newton tolerance sweep at h = " + format_number(r.scene.h) + " s (" + r.scene.name + ")";
  c.x_label = "wall-clock time per simulated second (s/s)";
  c.y_label = error_label(r);
  c.log_x = c.log_y = true;
  std::string tols;
  for (const Method& m : study_methods()) {
    if (!ran(r, m)) continue;
    // Explicit methods have no tolerance: an empty, unlabelled series keeps every method's
    // marker shape the same as in the other panels (shapes follow the series index).
    Series s;
    s.label = m.implicit() ? m.label : "";
    s.color = method_color(m.name);
    std::vector<std::tuple<double, double, double>> pts;  // tol, wall, error
    if (m.implicit())
      for (const StudyRow* row : plotted_rows(r, m.name, in_tol_sweep))
        pts.emplace_back(row->tol, row->wall_s, row->error);
    std::sort(pts.begin(), pts.end());
    for (const auto& [tol, wall, err] : pts) {
      s.x.push_back(wall);
      s.y.push_back(err);
      // The lecture's points carry their tolerance (the others sit on the same curve).
      s.point_labels.push_back(
          m.name == std::string("lecture") ? "tol = " + format_number(tol, "%.2g") : "");
    }
    c.series.push_back(s);
  }
  std::vector<double> tol_values;
  for (const StudyRow& row : r.rows)
    if (row.method == "lecture" && in_tol_sweep(r, row)) tol_values.push_back(row.tol);
  std::sort(tol_values.begin(), tol_values.end());
  c.notes.push_back("Newton stops when |p|_inf / h < tol; tol = " + join_times(tol_values) +
                    " m/s.");
  {
    double e_lo = INFINITY, e_hi = 0.0, w_lo = INFINITY, w_hi = 0.0, t_lo = 0.0, t_hi = 0.0;
    for (const StudyRow& row : r.rows)
      if (row.method == "lecture" && in_tol_sweep(r, row) && row.failure == "ok") {
        e_lo = std::min(e_lo, row.error);
        e_hi = std::max(e_hi, row.error);
        if (row.wall_s < w_lo) w_lo = row.wall_s, t_lo = row.tol;
        if (row.wall_s > w_hi) w_hi = row.wall_s, t_hi = row.tol;
      }
    if (std::isfinite(e_lo))
      c.notes.push_back("Lecture's method: error " + format_number(e_lo) + " ... " +
                        format_number(e_hi) + " over the tolerances that ran; " + "wall time " +
                        format_number(w_lo) + " s/s (tol = " + format_number(t_lo) + ") ... " +
                        format_number(w_hi) + " s/s (tol = " + format_number(t_hi) + ").");
  }
  add_failure_notes(r, in_tol_sweep, "tol", c.notes);
  return c;
}

// Error against n_seg over the mesh resolutions, against the finer mesh; each point
// labelled with its wall time. A y range within a factor of 1.5 is called narrow in the
// title, so a small change does not read as a large one.
ChartSpec mesh_panel(const StudyResult& r) {
  ChartSpec d;
  d.title = "Mesh resolution, lecture's method at h = " + format_number(r.scene.h) +
            " s, against a " + std::to_string(r.mesh_reference_n_seg) + "x" +
            std::to_string(r.mesh_reference_n_seg) +
            " mesh at h = " + format_number(r.mesh_reference_h) + " s";
  d.x_label = "segments per side (n_seg)";
  d.y_label = "RMS error at the coarse nodes / side length";
  d.log_y = true;  // n_seg on a linear axis: its few values each get a labelled tick
  Series s;
  s.label = "lecture's method (points labelled with wall time per simulated second)";
  s.color = method_color("lecture");
  double e_lo = INFINITY, e_hi = 0.0;
  for (const StudyRow& row : r.rows)
    if (in_mesh_sweep(r, row)) {
      if (std::isfinite(row.error) && row.error > 0.0) {
        s.x.push_back(row.n_seg);
        s.y.push_back(row.error);
        s.point_labels.push_back(format_number(row.wall_s, "%.3g") + " s/s");
        e_lo = std::min(e_lo, row.error);
        e_hi = std::max(e_hi, row.error);
      }
      d.notes.push_back(
          "n_seg = " + std::to_string(row.n_seg) + ": " + row.failure +
          (std::isfinite(row.error) ? ", error " + format_number(row.error) : std::string()) +
          ", " + format_number(row.wall_s) + " s/s");
    }
  if (s.x.size() >= 2 && e_hi < 1.5 * e_lo)
    d.title += "; narrow y range: every error lies between " + format_number(e_lo, "%.3g") +
               " and " + format_number(e_hi, "%.3g") + " (a spread of " +
               format_number(100.0 * (e_hi - e_lo) / e_lo, "%.2g") + "%)";
  d.series.push_back(s);
  d.notes.push_back("Coarse nodes are compared with the same material points of the fine mesh.");
  for (const std::string& f : r.reference_failures) d.notes.push_back(f);
  return d;
}

// A study whose every run failed has no point to plot: each panel says so first, in its
// title, rather than show empty axes and a slope of nan.
std::vector<ChartSpec> marked_if_all_failed(const StudyResult& r, std::vector<ChartSpec> panels) {
  if (!every_run_failed(r)) return panels;
  for (ChartSpec& panel : panels) {
    panel.title = "EVERY RUN FAILED (no error to plot; the notes list how each ended): " +
                  panel.title;
    panel.notes.insert(panel.notes.begin(),
                       "Every run of " + r.scene.name +
                           " failed, so nothing is plotted and no slope was fitted; "
                           "`invfree study` exited with status 3.");
  }
  return panels;
}

}  // namespace

std::vector<ChartSpec> study_panels(const StudyResult& r) {
  return marked_if_all_failed(r, {speed_accuracy_panel(r), convergence_panel(r)});
}

std::vector<ChartSpec> sweeps_panels(const StudyResult& r) {
  return marked_if_all_failed(r, {tolerance_panel(r), mesh_panel(r)});
}

}  // namespace invfree
