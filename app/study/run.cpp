#include "app/study/run.h"

#include <cmath>

#include "app/body_extent.h"
namespace invfree {

long step_count(double duration, double h) {
  return std::lround(duration / h);
}

std::string sample_steps(const std::vector<double>& times, double h, std::vector<long>* steps) {
  steps->clear();
  for (double t : times) {
    const long k = std::lround(t / h);
    if (std::abs(k * h - t) > 1e-9 * std::max(1.0, t))
      return "sample time " + std::to_string(t) +
             " s is not a multiple of h = " + std::to_string(h) + " s";
    steps->push_back(k);
  }
  return "";
}

namespace {

Frame capture(const Simulation& sim) {
  Frame f;
  f.mesh.triangles = sim.mesh.triangles;
  f.mesh.body_begin = sim.mesh.body_begin;
  f.x = sim.x;
  f.det_f = triangle_det_f(sim);
  f.has_ground = sim.scene.has_ground;
  f.has_ceiling = sim.scene.has_ceiling;
  f.ground_y = sim.scene.ground_y;
  f.ceiling_y = sim.ceiling_y;
  f.side = scene_length_scale(sim.scene);
  f.time = sim.time;
  return f;
}

}  // namespace

RunResult run_scene(const SceneDef& scene, const RunOptions& options) {
  RunResult result;
  if (std::string e = validate_scene(scene); !e.empty()) {
    result.verdict = Verdict::NotApplicable;
    result.fail_step = 0;
    result.message = e;
    return result;
  }
  std::vector<long> samples;
  if (std::string e = sample_steps(options.sample_times, scene.h, &samples); !e.empty()) {
    result.verdict = Verdict::NotApplicable;
    result.fail_step = 0;
    result.message = e;
    return result;
  }
  Simulation sim = make_simulation(scene);
  RunMonitor monitor;
  monitor.factor = options.blow_up_factor;
  monitor.inversion_is_failure = options.inversion_is_failure;
  monitor.inversion_allowed = options.inversion_allowed;
  monitor.start(sim, options.duration);
  const long total = step_count(options.duration, scene.h);
  size_t next_sample = 0;
  auto record = [&] {
    while (next_sample < samples.size() && samples[next_sample] == sim.step_count) {
      result.samples.push_back(sim.x);
      ++next_sample;
    }
  };
  record();
  for (long k = 0; k < total; ++k) {
    const StepReport r = step(sim);
    result.newton_iterations += r.newton_iterations;
    result.wall_s += r.wall_ms * 1e-3;
    if (r.status != StepStatus::Ok) {
      result.verdict = verdict_from_status(r.status);
      result.fail_step = sim.step_count + 1;
      result.message = r.message;
      break;
    }
    record();
    if (Verdict v = monitor.after_step(sim, &result.message); v != Verdict::Ok) {
      result.verdict = v;
      result.fail_step = sim.step_count;
      break;
    }
  }
  result.steps = sim.step_count;
  if (result.verdict == Verdict::Ok) {
    if (Verdict v = monitor.at_end(&result.message); v != Verdict::Ok) {
      result.verdict = v;
      result.fail_step = sim.step_count;
    }
  }
  if (result.verdict == Verdict::Ok && monitor.inversion_is_failure && monitor.inversion_allowed) {
    if (monitor.inverted_step >= 0) {
      result.verdict = Verdict::InvertedAllowed;
      result.fail_step = monitor.inverted_step;
      result.message = monitor.inverted_why;
    } else if (!monitor.recovered) {
      result.verdict = Verdict::InvertedAllowed;
      result.fail_step = sim.step_count;
      result.message = "started inverted and never recovered, which the model allows";
    }
  }
  if (monitor.inversion_is_failure) result.min_det_f = monitor.min_det_f;
  if (options.keep_frame) result.frame = capture(sim);
  return result;
}

}  // namespace invfree
