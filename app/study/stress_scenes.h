// The stress scenes of `invfree stability`, with their column headings. Their single
// source is the TOML files assets/scenes/stress-*.toml, embedded by invfree_scene_io
// (scene_io/builtin_scenes.h), so the command needs no asset path at run time, and
// `invfree simulate --scene assets/scenes/stress-h0.1.toml` runs the very same scene.
// They are run by path, not offered as built-in scene names. After them come the course's
// scenes that teach something under stress (course-5-moving-dirichlet, the course's squash),
// and a meshed shape (ring, the O-ring squashed: issue 27), embedded like every built-in
// scene.
#pragma once

#include <optional>
#include <span>
#include <string>

#include "scene/scene.h"

namespace invfree {

struct StressScene {
  std::string name;   // file stem, e.g. "stress-h0.1"
  std::string label;  // column heading, e.g. "h = 0.1 s"
  std::string toml;   // the file's text
};

// Every embedded stress scene and the course's stress columns, in the order of the
// stability table's columns.
const std::vector<StressScene>& stress_scenes();

// Parses and validates a stress scene; on failure returns nothing and sets `error`.
// (A scene the lecture's model cannot start, like stress-jitter-inverted, validates with
// the model its file names; a method switching to neo-Hookean then makes it n/a.)
std::optional<SceneDef> load_stress_scene(const StressScene& s, std::string* error);

// Simulated time of a stability run: until the ceiling has stopped, plus 0.5 s to settle
// (at least 2 s), rounded to whole steps of the scene's h.
double stability_duration(const SceneDef& scene);
// The quick run (`stability --quick`): until the scene's defining event, the ceiling
// reaching its stop (the squash; at least 1.5 s, which covers a drop or an impact), with
// no time to settle, rounded up to whole steps of the scene's h.
double quick_stability_duration(const SceneDef& scene);

}  // namespace invfree
