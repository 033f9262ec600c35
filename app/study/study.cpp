#include "app/study/study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "app/study/error.h"
#include "app/study/methods.h"
#include "app/study/run.h"

namespace invfree {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The sweeps, as multiples of the scene's h, tol and n_seg.
struct Plan {
  std::vector<double> implicit_h, explicit_h, tol;
  std::vector<int>
      mesh_divisor_or_multiplier;  // n_seg values as multiples of the scene's (negative: divide)
  int samples = 5;                 // sample times every 40 h (a multiple of every h swept)
  double reference_h_divisor = 1600.0;
  double reference_tol_factor = 1e-4;
  double mesh_reference_h_divisor = 10.0;
  int mesh_reference_multiplier = 4;
  double timing_budget_s = 0.25;  // repeat fast runs until this much wall time, keep the fastest
  int max_repeats = 25;
};

Plan make_plan(bool quick) {
  Plan p;
  if (quick) {
    p.implicit_h = {4, 2, 1, 0.5, 0.25};
    p.explicit_h = {0.1, 0.05, 0.025};
    p.tol = {10, 1, 0.1, 0.01};
    p.mesh_divisor_or_multiplier = {-2, 1};
    p.samples = 3;
    p.reference_h_divisor = 100.0;
    p.mesh_reference_multiplier = 2;
    p.timing_budget_s = 0.03;
    p.max_repeats = 3;
  } else {
    p.implicit_h = {4, 2, 1, 0.5, 0.25, 0.125, 1.0 / 16, 1.0 / 32, 1.0 / 64};
    p.explicit_h = {0.1, 0.05, 0.025, 0.0125, 0.00625};
    p.tol = {100, 10, 1, 0.1, 0.01, 0.001};
    p.mesh_divisor_or_multiplier = {-2, 1, 2};
  }
  return p;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Runs `scene` and, when it is fast, again until the timing budget is spent; keeps the
// fastest wall time (the results themselves are deterministic).
RunResult timed_run(const SceneDef& scene, const RunOptions& options, const Plan& plan) {
  RunResult best = run_scene(scene, options);
  double spent = best.wall_s;
  for (int rep = 1;
       best.verdict == Verdict::Ok && spent < plan.timing_budget_s && rep < plan.max_repeats;
       ++rep) {
    const RunResult again = run_scene(scene, options);
    spent += again.wall_s;
    best.wall_s = std::min(best.wall_s, again.wall_s);
  }
  return best;
}

}  // namespace

bool in_h_sweep(const StudyResult& r, const StudyRow& row) {
  return row.tol == r.scene.tol && row.n_seg == r.scene.n_seg;
}
bool in_tol_sweep(const StudyResult& r, const StudyRow& row) {
  const Method* m = find_method(row.method);
  return m && m->implicit() && row.h == r.scene.h && row.n_seg == r.scene.n_seg;
}
bool in_mesh_sweep(const StudyResult& r, const StudyRow& row) {
  return row.method == "lecture-mesh" && row.h == r.scene.h && row.tol == r.scene.tol;
}

StudyResult run_study(const SceneDef& scene, const StudyOptions& options) {
  const Plan plan = make_plan(options.quick);
  StudyResult result;
  result.scene = scene;
  const double interval = 40.0 * scene.h;
  for (int k = 1; k <= plan.samples; ++k) result.sample_times.push_back(k * interval);
  result.duration = result.sample_times.back();
  result.reference_h = scene.h / plan.reference_h_divisor;
  result.reference_tol = scene.tol * plan.reference_tol_factor;
  RunOptions run_options;
  run_options.duration = result.duration;
  run_options.sample_times = result.sample_times;
  run_options.inversion_is_failure = false;
  auto say = [&](const std::string& s) {
    if (options.progress) options.progress(s);
  };

  // Converged references, one per material model (lecture's solver settings).
  std::map<Model, std::vector<VecX>> references;
  auto reference_for = [&](Model model) -> const std::vector<VecX>* {
    auto it = references.find(model);
    if (it != references.end()) return it->second.empty() ? nullptr : &it->second;
    SceneDef ref = scene;
    std::string e = apply_method(*find_method("lecture"), ref, false);
    ref.model = model;
    ref.h = result.reference_h;
    ref.tol = result.reference_tol;
    ref.max_newton = std::max(ref.max_newton, 200);
    std::vector<VecX> samples;
    if (options.stop && (result.stopped = options.stop())) return nullptr;
    if (e.empty()) {
      const RunResult r = run_scene(ref, run_options);
      result.total_wall_s += r.wall_s;
      say(std::string("reference ") + model_name(model) + ": h = " + fmt(ref.h) +
          " s, tol = " + fmt(ref.tol) + " m/s, " + std::to_string(r.steps) + " steps, " +
          verdict_name(r.verdict) + ", " + fmt(r.wall_s) + " s");
      if (r.verdict == Verdict::Ok)
        samples = r.samples;
      else
        e = std::string(verdict_name(r.verdict)) + " at step " + std::to_string(r.fail_step) +
            ": " + r.message;
    }
    if (!e.empty())
      result.reference_failures.push_back(std::string("reference for ") + model_name(model) +
                                          " failed (" + e + "); its methods have no error");
    return (references[model] = samples).empty() ? nullptr : &references[model];
  };

  std::set<std::tuple<std::string, double, double, int>> done;
  auto add_row = [&](const Method& method, SceneDef s, const std::vector<VecX>* ref,
                     const std::vector<int>& map, const std::string& name) {
    if (result.stopped || (options.stop && (result.stopped = options.stop()))) return;
    if (!done.insert({name, s.h, s.tol, s.n_seg}).second) return;
    StudyRow row;
    row.method = name;
    row.h = s.h;
    row.tol = s.tol;
    row.n_seg = s.n_seg;
    row.error = kNaN;
    if (std::string e = apply_method(method, s, false); !e.empty()) {
      row.failure = verdict_name(Verdict::NotApplicable);
      row.message = e;
      row.wall_s = kNaN;
      row.newton_iters = kNaN;
      result.rows.push_back(row);
      return;
    }
    const RunResult r = timed_run(s, run_options, plan);
    result.total_wall_s += r.wall_s;
    row.failure = verdict_name(r.verdict);
    row.fail_step = r.fail_step;
    row.message = r.message;
    const double simulated = std::max<long>(r.steps, 1) * s.h;
    row.wall_s = r.verdict == Verdict::NotApplicable ? kNaN : r.wall_s / simulated;
    const long attempted =
        r.steps + (r.verdict == Verdict::Ok || r.verdict == Verdict::NotApplicable ? 0 : 1);
    row.newton_iters = attempted > 0 ? static_cast<double>(r.newton_iterations) / attempted : 0.0;
    if (r.verdict == Verdict::Ok && ref)
      row.error = rms_position_error(r.samples, *ref, s.side, map);
    say(name + ": h = " + fmt(s.h) + " s, tol = " + fmt(s.tol) +
        " m/s, n_seg = " + std::to_string(s.n_seg) + ": " + row.failure +
        (r.verdict == Verdict::Ok ? ", error " + fmt(row.error)
                                  : " at step " + std::to_string(r.fail_step)) +
        ", " + fmt(row.wall_s) + " s per simulated s");
    result.rows.push_back(row);
  };

  for (const Method& method : study_methods()) {
    SceneDef probe = scene;
    apply_method(method, probe, false);
    const std::vector<VecX>* ref = reference_for(probe.model);
    for (double f : method.implicit() ? plan.implicit_h : plan.explicit_h) {
      SceneDef s = scene;
      s.h = scene.h * f;
      add_row(method, s, ref, {}, method.name);
    }
    if (method.implicit())
      for (double f : plan.tol) {
        SceneDef s = scene;
        s.tol = scene.tol * f;
        add_row(method, s, ref, {}, method.name);
      }
  }

  // Mesh resolution, lecture's method: compared at the shared nodes with a finer mesh.
  const Method& lecture = *find_method("lecture");
  std::vector<int> n_values;
  for (int m : plan.mesh_divisor_or_multiplier) {
    if (m < 0 && scene.n_seg % (-m) != 0) continue;
    n_values.push_back(m < 0 ? scene.n_seg / (-m) : scene.n_seg * m);
  }
  result.mesh_reference_n_seg = scene.n_seg * plan.mesh_reference_multiplier;
  result.mesh_reference_h = scene.h / plan.mesh_reference_h_divisor;
  SceneDef mesh_ref = scene;
  apply_method(lecture, mesh_ref, false);
  mesh_ref.n_seg = result.mesh_reference_n_seg;
  mesh_ref.h = result.mesh_reference_h;
  mesh_ref.tol = result.reference_tol;
  mesh_ref.max_newton = std::max(mesh_ref.max_newton, 200);
  if (result.stopped || (options.stop && (result.stopped = options.stop()))) return result;
  const RunResult fine = run_scene(mesh_ref, run_options);
  result.total_wall_s += fine.wall_s;
  say("mesh reference: n_seg = " + std::to_string(mesh_ref.n_seg) + ", h = " + fmt(mesh_ref.h) +
      " s, " + verdict_name(fine.verdict) + ", " + fmt(fine.wall_s) + " s");
  if (fine.verdict != Verdict::Ok)
    result.reference_failures.push_back(
        "mesh reference (n_seg = " + std::to_string(mesh_ref.n_seg) + ") failed (" +
        verdict_name(fine.verdict) + ": " + fine.message + ")");
  for (int n : n_values) {
    SceneDef s = scene;
    s.n_seg = n;
    // Rows named "lecture-mesh": every resolution, the scene's own included, measured
    // against the fine mesh (the "lecture" rows use the same-mesh temporal reference).
    add_row(lecture, s, fine.verdict == Verdict::Ok ? &fine.samples : nullptr,
            nested_node_map(n, mesh_ref.n_seg), "lecture-mesh");
  }

  // The classic convergence check on the contact-free version of the scene.
  {
    SceneDef smooth = scene;
    smooth.has_ground = smooth.has_ceiling = false;
    apply_method(lecture, smooth, false);
    SceneDef ref = smooth;
    ref.h = result.reference_h;
    ref.tol = result.reference_tol;
    ref.max_newton = std::max(ref.max_newton, 200);
    if (!(result.stopped || (options.stop && (result.stopped = options.stop())))) {
      const RunResult r = run_scene(ref, run_options);
      result.total_wall_s += r.wall_s;
      say("reference without contact: " + std::string(verdict_name(r.verdict)) + ", " +
          fmt(r.wall_s) + " s");
      if (r.verdict != Verdict::Ok)
        result.reference_failures.push_back("reference without contact failed (" +
                                            std::string(verdict_name(r.verdict)) + ": " +
                                            r.message + ")");
      for (double f : plan.implicit_h) {
        SceneDef s = smooth;
        s.h = scene.h * f;
        add_row(lecture, s, r.verdict == Verdict::Ok ? &r.samples : nullptr, {},
                "lecture-no-contact");
      }
    }
  }

  std::vector<double> hs, errs, smooth_hs, smooth_errs;
  for (const StudyRow& row : result.rows)
    if (row.method == "lecture" && in_h_sweep(result, row)) {
      hs.push_back(row.h);
      errs.push_back(row.error);
    }
  result.lecture_slope = loglog_slope(hs, errs);
  {
    // The same fit over the four smallest steps only: where the asymptotic order shows first.
    std::vector<std::pair<double, double>> pts;
    for (size_t i = 0; i < hs.size(); ++i)
      if (std::isfinite(errs[i])) pts.emplace_back(hs[i], errs[i]);
    std::sort(pts.begin(), pts.end());
    pts.resize(std::min<size_t>(pts.size(), 4));
    std::vector<double> x, y;
    for (const auto& [h, e] : pts) {
      x.push_back(h);
      y.push_back(e);
    }
    result.lecture_slope_small_h = loglog_slope(x, y);
  }
  for (const StudyRow& row : result.rows)
    if (row.method == "lecture-no-contact") {
      smooth_hs.push_back(row.h);
      smooth_errs.push_back(row.error);
    }
  result.smooth_slope = loglog_slope(smooth_hs, smooth_errs);
  return result;
}

std::string study_csv(const StudyResult& result) {
  std::ostringstream o;
  o << "method,h,tol,n_seg,wall_s,error,newton_iters,failure\n";
  o.precision(8);
  auto num = [](double v) -> std::string {
    if (!std::isfinite(v)) return "";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
  };
  for (const StudyRow& r : result.rows)
    o << r.method << "," << num(r.h) << "," << num(r.tol) << "," << r.n_seg << "," << num(r.wall_s)
      << "," << num(r.error) << "," << num(r.newton_iters) << "," << r.failure << "\n";
  return o.str();
}

}  // namespace invfree
