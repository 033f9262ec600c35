#include "app/live/live_controller.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "energy_report.h"

namespace invfree::live {

LiveController::LiveController(std::vector<SceneChoice> scenes, int selected)
    : scenes_(std::move(scenes)) {
  if (scenes_.empty()) throw std::invalid_argument("LiveController: no scene");
  selected_ = std::clamp(selected, 0, static_cast<int>(scenes_.size()) - 1);
  restart(scenes_[selected_].scene);
}

void LiveController::restart(const SceneDef& scene) {
  sim_ = make_simulation(scene);
  ++restarts_;
  pull_node_ = -1;
  sync_pull();
  banner.clear();
  has_report_ = false;
  last_report_ = StepReport{};
  ms_history_.clear();
  min_det_history_.clear();
  for (StatsHistory& h : energy_history_) h.clear();
  gravitational_start_ = energy_report(sim_).gravitational;
  measure();
}

void LiveController::measure() {
  ++revision_;
  det_f_ = triangle_det_f(sim_);
  stats_ = StateStats{};
  if (det_f_.empty()) return;
  const auto [lo, hi] = std::minmax_element(det_f_.begin(), det_f_.end());
  stats_.min_det_f = *lo;
  stats_.max_det_f = *hi;
  stats_.inverted = static_cast<int>(
      std::count_if(det_f_.begin(), det_f_.end(), [](double d) { return !(d > 0.0); }));
}

int LiveController::advance_frame() {
  if (!playing_) return 0;
  int taken = 0;
  for (int k = 0; k < std::max(1, steps_per_frame); ++k) {
    if (!step_once()) break;
    ++taken;
  }
  return taken;
}

bool LiveController::step_once() {
  sync_pull();
  const StepReport r = step(sim_);
  if (r.status != StepStatus::Ok) {
    playing_ = false;
    banner = "Step " + std::to_string(sim_.step_count + 1) + " failed (" +
             step_status_name(r.status) + (r.message.empty() ? "" : ": " + r.message) +
             "). Paused with the last good state; change a setting, or press R to reset.";
    return false;
  }
  last_report_ = r;
  has_report_ = true;
  ++steps_total_;
  step_ms_total_ += r.wall_ms;
  banner.clear();
  measure();
  ms_history_.push(static_cast<float>(r.wall_ms));
  min_det_history_.push(static_cast<float>(stats_.min_det_f));
  const EnergyReport e = energy_report(sim_);
  const double energies[4] = {e.kinetic, e.elastic, e.gravitational - gravitational_start_,
                              e.contact};
  for (int k = 0; k < 4; ++k) energy_history_[k].push(static_cast<float>(energies[k]));
  return true;
}

void LiveController::reset() {
  restart(sim_.scene);
  note.clear();
}

bool LiveController::apply(const SceneDef& next) {
  if (next == sim_.scene) return true;
  if (const std::string e = validate_scene(next); !e.empty()) {
    note = "not applied: " + e;
    return false;
  }
  if (!model_allows_inversion(next.model) && model_allows_inversion(sim_.scene.model) &&
      stats_.inverted > 0) {
    note = std::string("not applied: ") + model_name(next.model) + " needs det F > 0, but " +
           std::to_string(stats_.inverted) + " triangle(s) are inverted now; press R (reset) first";
    return false;
  }
  if (needs_new_mesh(sim_.scene, next)) {
    ++mesh_generation_;
    restart(next);
    note = "mesh rebuilt (n_seg = " + std::to_string(next.n_seg) +
           "); restarted from the initial state";
    return true;
  }
  update_scene(sim_, next);
  measure();
  return true;
}

void LiveController::select_scene(int index) {
  selected_ = std::clamp(index, 0, static_cast<int>(scenes_.size()) - 1);
  ++mesh_generation_;
  restart(scenes_[selected_].scene);
  playing_ = false;
  note.clear();
}

bool LiveController::restart_with(const SceneDef& next) {
  if (const std::string e = validate_scene(next); !e.empty()) {
    note = "not applied: " + e;
    return false;
  }
  if (needs_new_mesh(sim_.scene, next)) ++mesh_generation_;
  restart(next);
  note.clear();
  return true;
}

void LiveController::begin_pull(int node, const Vec2& target) {
  if (node < 0 || node >= sim_.mesh.node_count() || !target.allFinite()) return;
  pull_node_ = node;
  pull_target_ = target;
  sync_pull();
}

void LiveController::move_pull(const Vec2& target) {
  if (pull_node_ < 0 || !target.allFinite()) return;
  pull_target_ = target;
  sync_pull();
}

void LiveController::end_pull() {
  pull_node_ = -1;
  sync_pull();
}

void LiveController::sync_pull() {
  sim_.pull.on = pull_node_ >= 0;
  sim_.pull.node = std::max(pull_node_, 0);
  sim_.pull.target = pull_target_;
  sim_.pull.stiffness = pull_stiffness;
}

int LiveController::nearest_node(const Vec2& p, double radius) const {
  int best = -1;
  double best_d2 = radius * radius;
  for (int i = 0; i < sim_.mesh.node_count(); ++i) {
    const double d2 = (sim_.x.segment<2>(2 * i) - p).squaredNorm();
    if (d2 <= best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  return best;
}

}  // namespace invfree::live
