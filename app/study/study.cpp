#include "app/study/study.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "app/body_extent.h"
#include "app/format_number.h"
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
  // Sample times every 40 h (a multiple of every h swept), also in a quick study: the last
  // is the run's end, and a quick run that stopped earlier (it ran 3 samples, 1.2 s of
  // compress, before the ceiling squeezes the square) called symplectic Euler ok where the
  // full study sees it penetrate at every h.
  int samples = 5;
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

// One study while it runs: the plan, what every run shares, the references computed so
// far (one per material model) and the rows already run (a point of several sweeps runs
// once).
struct StudyRun {
  const SceneDef& scene;
  const SweepOptions& options;
  Plan plan;
  RunOptions run_options;
  StudyResult result;
  std::map<Model, std::vector<VecX>> references;
  std::set<std::tuple<std::string, double, double, int>> done;

  StudyRun(const SceneDef& s, const SweepOptions& o)
      : scene(s), options(o), plan(make_plan(o.quick)) {
    result.scene = scene;
    result.sample_times = study_sample_times(scene, o.quick);
    for (const Method& m : study_methods())
      if (o.wants(m.name)) result.methods.push_back(m.name);
    result.duration = result.sample_times.back();
    result.reference_h = scene.h / plan.reference_h_divisor;
    result.reference_tol = scene.tol * plan.reference_tol_factor;
    run_options.duration = result.duration;
    run_options.sample_times = result.sample_times;
    run_options.inversion_is_failure = false;
  }
  // True once the caller asked to stop (asked again before every run).
  bool stopped() { return result.stopped || (result.stopped = options.stop_requested()); }
  // A run whose wall time counts in the total (references and rows).
  RunResult run(const SceneDef& s) {
    const RunResult r = run_scene(s, run_options);
    result.total_wall_s += r.wall_s;
    return r;
  }
};

// `s` with the converged reference's settings: step h, tolerance tol, Newton cap >= 200.
SceneDef converged(SceneDef s, double h, double tol) {
  s.h = h;
  s.tol = tol;
  s.max_newton = std::max(s.max_newton, 200);
  return s;
}

// The converged reference of `model` on the scene (lecture's solver settings), computed on
// first use; null when it failed (then recorded in reference_failures) or when stopped.
const std::vector<VecX>* reference_for(StudyRun& study, Model model) {
  StudyResult& result = study.result;
  auto it = study.references.find(model);
  if (it != study.references.end()) return it->second.empty() ? nullptr : &it->second;
  SceneDef ref = study.scene;
  std::string e = apply_method(*find_method("lecture"), ref, false);
  ref.model = model;
  ref = converged(ref, result.reference_h, result.reference_tol);
  std::vector<VecX> samples;
  if (study.stopped()) return nullptr;
  if (e.empty()) {
    const RunResult r = study.run(ref);
    study.options.report(
        std::string("reference ") + model_name(model) + ": h = " + format_number(ref.h, "%.6g") +
        " s, tol = " + format_number(ref.tol, "%.6g") + " m/s, " + std::to_string(r.steps) +
        " steps, " + verdict_name(r.verdict) + ", " + format_number(r.wall_s, "%.6g") + " s");
    if (r.verdict == Verdict::Ok)
      samples = r.samples;
    else
      e = std::string(verdict_name(r.verdict)) + " at step " + std::to_string(r.fail_step) + ": " +
          r.message;
  }
  if (!e.empty())
    result.reference_failures.push_back(std::string("reference for ") + model_name(model) +
                                        " failed (" + e + "); its methods have no error");
  auto& kept = study.references[model] = samples;
  return kept.empty() ? nullptr : &kept;
}

// Runs `method` on `s` (timed_run) and adds its row named `name`: the verdict, the wall time
// per simulated second, Newton iterations per step and, when it ran to the end and `ref` is
// given, the error against `ref` (node i compared with node map[i]).
void add_row(StudyRun& study, const Method& method, SceneDef s, const std::vector<VecX>* ref,
             const std::vector<int>& map, const std::string& name) {
  if (study.stopped()) return;
  if (!study.done.insert({name, s.h, s.tol, s.n_seg}).second) return;
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
    study.result.rows.push_back(row);
    return;
  }
  const RunResult r = timed_run(s, study.run_options, study.plan);
  study.result.total_wall_s += r.wall_s;
  row.failure = verdict_name(r.verdict);
  row.fail_step = r.fail_step;
  row.message = r.message;
  const double simulated = std::max<long>(r.steps, 1) * s.h;
  row.wall_s = r.verdict == Verdict::NotApplicable ? kNaN : r.wall_s / simulated;
  const long attempted =
      r.steps + (r.verdict == Verdict::Ok || r.verdict == Verdict::NotApplicable ? 0 : 1);
  row.newton_iters = attempted > 0 ? static_cast<double>(r.newton_iterations) / attempted : 0.0;
  if (r.verdict == Verdict::Ok && ref)
    row.error = rms_position_error(r.samples, *ref, scene_length_scale(s), map);
  study.options.report(name + ": h = " + format_number(s.h, "%.6g") +
                       " s, tol = " + format_number(s.tol, "%.6g") +
                       " m/s, n_seg = " + std::to_string(s.n_seg) + ": " + row.failure +
                       (r.verdict == Verdict::Ok ? ", error " + format_number(row.error, "%.6g")
                                                 : " at step " + std::to_string(r.fail_step)) +
                       ", " + format_number(row.wall_s, "%.6g") + " s per simulated s");
  study.result.rows.push_back(row);
}

// Every method over the plan's h (implicit methods around the scene's h, symplectic Euler
// below it) and every implicit method over the plan's tolerances, each against the
// reference of its material model.
void sweep_methods(StudyRun& study) {
  const SceneDef& scene = study.scene;
  for (const Method& method : study_methods()) {
    if (!study.options.wants(method.name)) continue;
    SceneDef probe = scene;
    apply_method(method, probe, false);
    const std::vector<VecX>* ref = reference_for(study, probe.model);
    for (double f : method.implicit() ? study.plan.implicit_h : study.plan.explicit_h) {
      SceneDef s = scene;
      s.h = scene.h * f;
      add_row(study, method, s, ref, {}, method.name);
    }
    if (method.implicit())
      for (double f : study.plan.tol) {
        SceneDef s = scene;
        s.tol = scene.tol * f;
        add_row(study, method, s, ref, {}, method.name);
      }
  }
}

// Mesh resolution, lecture's method: rows "lecture-mesh", every resolution (the scene's own
// included) compared at the shared nodes with a finer mesh at a smaller h (the "lecture"
// rows use the same-mesh temporal reference).
void sweep_mesh(StudyRun& study) {
  const SceneDef& scene = study.scene;
  StudyResult& result = study.result;
  if (!scene_has_only_squares(scene)) {
    // The error compares nodes a coarse grid shares with the finer one (nested_node_map);
    // CGAL's meshes of a shape at two n_seg share no interior node, so there is no such
    // comparison: the sweep is left out rather than shown against the wrong nodes.
    study.options.report(
        "mesh sweep left out: a meshed shape's meshes at different n_seg "
        "share no nodes to compare");
    return;
  }
  const Method& lecture = *find_method("lecture");
  std::vector<int> n_values;
  for (int m : study.plan.mesh_divisor_or_multiplier) {
    if (m < 0 && scene.n_seg % (-m) != 0) continue;
    n_values.push_back(m < 0 ? scene.n_seg / (-m) : scene.n_seg * m);
  }
  result.mesh_reference_n_seg = scene.n_seg * study.plan.mesh_reference_multiplier;
  result.mesh_reference_h = scene.h / study.plan.mesh_reference_h_divisor;
  SceneDef mesh_ref = scene;
  apply_method(lecture, mesh_ref, false);
  mesh_ref.n_seg = result.mesh_reference_n_seg;
  mesh_ref = converged(mesh_ref, result.mesh_reference_h, result.reference_tol);
  if (study.stopped()) return;
  const RunResult fine = study.run(mesh_ref);
  study.options.report("mesh reference: n_seg = " + std::to_string(mesh_ref.n_seg) + ", h = " +
                       format_number(mesh_ref.h, "%.6g") + " s, " + verdict_name(fine.verdict) +
                       ", " + format_number(fine.wall_s, "%.6g") + " s");
  if (fine.verdict != Verdict::Ok)
    result.reference_failures.push_back(
        "mesh reference (n_seg = " + std::to_string(mesh_ref.n_seg) + ") failed (" +
        verdict_name(fine.verdict) + ": " + fine.message + ")");
  for (int n : n_values) {
    SceneDef s = scene;
    s.n_seg = n;
    add_row(study, lecture, s, fine.verdict == Verdict::Ok ? &fine.samples : nullptr,
            nested_node_map(n, mesh_ref.n_seg), "lecture-mesh");
  }
}

// The classic convergence check: the lecture's method over the plan's implicit h on the
// scene without ground and ceiling (rows "lecture-no-contact"), against its own reference.
void sweep_without_contact(StudyRun& study) {
  const SceneDef& scene = study.scene;
  StudyResult& result = study.result;
  const Method& lecture = *find_method("lecture");
  SceneDef smooth = scene;
  smooth.has_ground = smooth.has_ceiling = false;
  apply_method(lecture, smooth, false);
  const SceneDef ref = converged(smooth, result.reference_h, result.reference_tol);
  if (study.stopped()) return;
  const RunResult r = study.run(ref);
  study.options.report("reference without contact: " + std::string(verdict_name(r.verdict)) + ", " +
                       format_number(r.wall_s, "%.6g") + " s");
  if (r.verdict != Verdict::Ok)
    result.reference_failures.push_back("reference without contact failed (" +
                                        std::string(verdict_name(r.verdict)) + ": " + r.message +
                                        ")");
  for (double f : study.plan.implicit_h) {
    SceneDef s = smooth;
    s.h = scene.h * f;
    add_row(study, lecture, s, r.verdict == Verdict::Ok ? &r.samples : nullptr, {},
            "lecture-no-contact");
  }
}

// The fitted convergence slopes d log(error) / d log(h): the lecture's method on the scene
// (over all its h, and over its four smallest, where the asymptotic order shows first) and
// without contact.
void fit_slopes(StudyResult& result) {
  std::vector<double> hs, errs, smooth_hs, smooth_errs;
  for (const StudyRow& row : result.rows)
    if (row.method == "lecture" && in_h_sweep(result, row)) {
      hs.push_back(row.h);
      errs.push_back(row.error);
    }
  result.lecture_slope = loglog_slope(hs, errs);
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
  for (const StudyRow& row : result.rows)
    if (row.method == "lecture-no-contact") {
      smooth_hs.push_back(row.h);
      smooth_errs.push_back(row.error);
    }
  result.smooth_slope = loglog_slope(smooth_hs, smooth_errs);
}

void fit_convergence(StudyResult& result) {
  for (const std::string& name : study_methods_run(result)) {
    const std::string model = method_model(*find_method(name));
    if (model_convergence(result, model)) continue;
    std::vector<double> hs, errs;
    for (const StudyRow& row : result.rows) {
      const Method* m = find_method(row.method);
      if (!m || method_model(*m) != model || !in_h_sweep(result, row)) continue;
      if (!(std::isfinite(row.error) && row.error > 0.0)) continue;
      hs.push_back(row.h);
      errs.push_back(row.error);
    }
    ModelConvergence c;
    c.model = model;
    c.points = static_cast<int>(hs.size());
    c.slope = hs.size() >= 3 ? loglog_slope(hs, errs) : kNaN;
    if (!errs.empty()) {
      c.error_lo = *std::min_element(errs.begin(), errs.end());
      c.error_hi = *std::max_element(errs.begin(), errs.end());
    }
    c.judged = std::isfinite(c.slope);
    c.converges = c.judged && c.slope >= kMinConvergenceSlope && c.error_lo <= kMaxConvergedError;
    result.convergence.push_back(c);
  }
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

std::vector<double> study_sample_times(const SceneDef& scene, bool quick) {
  const Plan plan = make_plan(quick);
  std::vector<double> t;
  for (int k = 1; k <= plan.samples; ++k) t.push_back(k * 40.0 * scene.h);
  return t;
}

StudyResult run_study(const SceneDef& scene, const SweepOptions& options) {
  StudyRun study(scene, options);
  sweep_methods(study);
  // The mesh sweep and the check without contact are the lecture's method's.
  if (options.wants("lecture")) {
    sweep_mesh(study);
    sweep_without_contact(study);
  }
  fit_slopes(study.result);
  fit_convergence(study.result);
  return study.result;
}

bool study_ran_method(const StudyResult& result, const std::string& method) {
  return result.methods.empty() ||
         std::find(result.methods.begin(), result.methods.end(), method) != result.methods.end();
}

std::vector<std::string> study_methods_run(const StudyResult& result) {
  std::vector<std::string> out;
  for (const Method& m : study_methods())
    if (study_ran_method(result, m.name)) out.push_back(m.name);
  return out;
}

const ModelConvergence* model_convergence(const StudyResult& result, const std::string& model) {
  for (const ModelConvergence& c : result.convergence)
    if (c.model == model) return &c;
  return nullptr;
}

std::vector<const ModelConvergence*> non_converging_models(const StudyResult& result) {
  std::vector<const ModelConvergence*> out;
  for (const ModelConvergence& c : result.convergence)
    if (c.judged && !c.converges) out.push_back(&c);
  return out;
}

bool every_run_failed(const StudyResult& result) {
  return std::none_of(result.rows.begin(), result.rows.end(),
                      [](const StudyRow& row) { return row.failure == "ok"; });
}

std::string study_csv(const StudyResult& result) {
  std::ostringstream o;
  o << "method,h,tol,n_seg,wall_s,error,newton_iters,failure\n";
  o.precision(8);
  auto num = [](double v) { return std::isfinite(v) ? format_number(v, "%.6g") : std::string(); };
  for (const StudyRow& r : result.rows)
    o << r.method << "," << num(r.h) << "," << num(r.tol) << "," << r.n_seg << "," << num(r.wall_s)
      << "," << num(r.error) << "," << num(r.newton_iters) << "," << r.failure << "\n";
  return o.str();
}

}  // namespace invfree
