// The live mode's simulation controller, independent of any window: it owns the running
// Simulation, the settings the panel edits, play/pause/step/reset, the grab spring, the
// per-state measurements (det F per triangle, min/max, inverted count) and the short
// histories the panel plots.
//
// Every settings change goes through `apply`, which validates the whole scene and hands
// it to core update_scene(): the state is kept (so a change in the middle of a
// compression continues from a valid state) unless the mesh definition changed, which
// rebuilds the mesh and restarts. Switching to a model that forbids inversion while some
// triangle is inverted is refused with a note (its energy would be infinite there).
// A failed step (Newton cap, non-finite values, broken invariant) pauses, keeps the last
// good state (core step() leaves it untouched) and sets `banner`.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "app/live/stats_history.h"
#include "simulation.h"

namespace invfree::live {

struct SceneChoice {
  std::string label;  // built-in name or file path, as shown in the scene picker
  SceneDef scene;     // as loaded (with the command line's --set overrides)
};

struct StateStats {
  double min_det_f = 1.0, max_det_f = 1.0;
  int inverted = 0;  // triangles with det F <= 0
};

class LiveController {
 public:
  // `scenes` must not be empty; every scene must be valid (validate_scene).
  LiveController(std::vector<SceneChoice> scenes, int selected);

  // --- playback
  bool playing() const { return playing_; }
  void set_playing(bool on) { playing_ = on; }
  int steps_per_frame = 1;
  // Advances one displayed frame: steps_per_frame steps when playing. Returns the
  // number of steps taken (fewer when one failed).
  int advance_frame();
  // One step. On failure: pauses, sets `banner`, keeps the last good state; returns false.
  bool step_once();
  // Back to the initial state of the current settings.
  void reset();

  // --- settings
  const SceneDef& settings() const { return sim_.scene; }
  // Validates `next` and applies it (see the header comment). Returns true when applied;
  // otherwise `note` says why and nothing changed.
  bool apply(const SceneDef& next);
  // Validates `next` and restarts from its initial state (the method picker: another
  // solver from t = 0, not from a state the old one reached). Returns true when applied;
  // otherwise `note` says why and nothing changed.
  bool restart_with(const SceneDef& next);
  const std::vector<SceneChoice>& scenes() const { return scenes_; }
  int selected_scene() const { return selected_; }
  // Loads that scene's settings and restarts it paused at t = 0: a class sees a new scene's
  // start, and it plays when the teacher presses Space.
  void select_scene(int index);
  void restore_scene_defaults() { select_scene(selected_); }

  // --- the grab spring: node `node` pulled toward `target` while dragging
  double pull_stiffness = 1e5;  // N/m: the demo's square (1000 kg) hangs ~0.1 m below the cursor
  void begin_pull(int node, const Vec2& target);
  void move_pull(const Vec2& target);
  void end_pull();
  bool pulling() const { return pull_node_ >= 0; }
  int pull_node() const { return pull_node_; }
  Vec2 pull_target() const { return pull_target_; }

  // --- state and measurements
  const Simulation& simulation() const { return sim_; }
  const std::vector<double>& det_f() const { return det_f_; }  // per triangle, current state
  const StateStats& stats() const { return stats_; }
  const StepReport& last_report() const { return last_report_; }
  bool has_stepped() const { return has_report_; }
  const StatsHistory& ms_history() const { return ms_history_; }
  // Every successful step since the controller was made (for the benchmark line).
  long steps_total() const { return steps_total_; }
  double step_ms_total() const { return step_ms_total_; }
  const StatsHistory& min_det_history() const { return min_det_history_; }
  // Kinetic, elastic, gravitational and contact energy (J, core/energy_report.h) over the
  // last steps, in that order (kEnergyNames); gravitational as its change since the
  // (re)start, so that the exchange between the four shows on one axis.
  static constexpr const char* kEnergyNames[4] = {"kinetic", "elastic", "\xce\x94gravity",
                                                  "contact"};
  const std::array<StatsHistory, 4>& energy_history() const { return energy_history_; }
  // Changes whenever the state or the settings change (a picture of an unchanged
  // revision need not be drawn again).
  long revision() const { return revision_; }
  // Changes whenever the mesh is rebuilt (another scene, n_seg, springs <-> triangles), not
  // on a reset: a triangle's index names the same triangle while it stays.
  long mesh_generation() const { return mesh_generation_; }
  // Changes on every restart from an initial state (reset, another scene, a new mesh):
  // what is gathered over a run (the colour range's run bounds) starts again.
  long restarts() const { return restarts_; }
  // Node closest to `p` within `radius` (world units), or -1.
  int nearest_node(const Vec2& p, double radius) const;

  // Messages for the panel: `note` explains the last clamped/refused edit or a rebuild;
  // `banner` is set while paused after a failed step.
  std::string note;
  std::string banner;

 private:
  void restart(const SceneDef& scene);
  void measure();
  void sync_pull();

  std::vector<SceneChoice> scenes_;
  int selected_ = 0;
  Simulation sim_;
  bool playing_ = true;
  std::vector<double> det_f_;
  StateStats stats_;
  StepReport last_report_;
  bool has_report_ = false;
  StatsHistory ms_history_{400}, min_det_history_{400};
  double gravitational_start_ = 0.0;
  std::array<StatsHistory, 4> energy_history_{StatsHistory(400), StatsHistory(400),
                                              StatsHistory(400), StatsHistory(400)};
  long revision_ = 0;
  long mesh_generation_ = 0;
  long restarts_ = 0;
  long steps_total_ = 0;
  double step_ms_total_ = 0.0;
  int pull_node_ = -1;
  Vec2 pull_target_ = Vec2::Zero();
};

}  // namespace invfree::live
