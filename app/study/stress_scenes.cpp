#include "app/study/stress_scenes.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "scene_io/builtin_scenes.h"

namespace invfree {

namespace {

// Column order and headings; a file not listed here goes last under its own name.
const std::vector<std::pair<std::string, std::string>>& headings() {
  static const std::vector<std::pair<std::string, std::string>> h = {
      {"stress-h0.05", "h = 0.05 s"},
      {"stress-h0.1", "h = 0.1 s"},
      {"stress-nu0.49", "\u03bd = 0.49"},
      {"stress-nu0.499", "\u03bd = 0.499"},
      {"stress-squash10", "squash to 10%"},
      {"stress-squash5", "squash to 5%"},
      {"stress-impact", "impact at 20 m/s"},
      {"stress-soft", "E = 1e3 Pa"},
      {"stress-stiff", "E = 1e8 Pa"},
      {"stress-jitter", "jittered start (35%)"},
      {"stress-jitter-inverted", "jittered start, inverted (45%)"},
      {"stress-fold", "64x64 fold (self-contact)"},
      {"stress-stack-drop", "stack thrown at 20 m/s"},
      {"course-5-moving-dirichlet", "the course's squash (chapter 5)"},
      {"ring", "O-ring squashed (meshed shape)"},
  };
  return h;
}

// The course's scenes that are stress scenes too, last: chapter 5 squashes the square to
// 40% of its height; its springs (the mass-spring row) invert, the neo-Hookean rows hold.
// The other chapters squeeze nothing: as columns, every method is ok on chapters 1, 2 and
// 4, and on chapter 3 only symplectic Euler fails (it penetrates, as on every stress scene).
const std::vector<std::string>& course_columns() {
  static const std::vector<std::string> c = {"course-5-moving-dirichlet"};
  return c;
}

// A meshed shape (issue 27), last: the O-ring squashed until its hole closes, its inner
// boundary held off itself by self-contact; an unstructured CGAL mesh instead of the grid.
const std::vector<std::string>& shape_columns() {
  static const std::vector<std::string> c = {"ring"};
  return c;
}

}  // namespace

const std::vector<StressScene>& stress_scenes() {
  static const std::vector<StressScene> scenes = [] {
    std::vector<StressScene> v;
    for (const EmbeddedScene& e : stress_scene_files())
      v.push_back({std::string(e.name), std::string(e.name), std::string(e.text)});
    for (const EmbeddedScene& e : builtin_scenes())
      if (std::ranges::find(course_columns(), e.name) != course_columns().end() ||
          std::ranges::find(shape_columns(), e.name) != shape_columns().end())
        v.push_back({std::string(e.name), std::string(e.name), std::string(e.text)});
    const auto& h = headings();
    auto rank = [&](const std::string& name) {
      for (size_t k = 0; k < h.size(); ++k)
        if (h[k].first == name) return static_cast<long>(k);
      return static_cast<long>(h.size());
    };
    for (StressScene& s : v)
      if (rank(s.name) < static_cast<long>(h.size())) s.label = h[rank(s.name)].second;
    std::stable_sort(v.begin(), v.end(), [&](const StressScene& a, const StressScene& b) {
      return rank(a.name) < rank(b.name) || (rank(a.name) == rank(b.name) && a.name < b.name);
    });
    return v;
  }();
  return scenes;
}

std::optional<SceneDef> load_stress_scene(const StressScene& s, std::string* error) {
  SceneLoad load = parse_scene_toml(s.toml, "assets/scenes/" + s.name + ".toml");
  if (!load.scene) {
    *error = load.error;
    return std::nullopt;
  }
  if (std::string e = validate_scene(*load.scene); !e.empty()) {
    *error = "assets/scenes/" + s.name + ".toml: " + e;
    return std::nullopt;
  }
  return load.scene;
}

namespace {

// When the ceiling reaches its stop (at least 1.5 s).
double event_time(const SceneDef& scene) {
  double t = 1.5;
  if (scene.has_ceiling && scene.ceiling_velocity < 0.0 && scene.ceiling_y > scene.ceiling_stop)
    t = std::max(t, (scene.ceiling_y - scene.ceiling_stop) / -scene.ceiling_velocity);
  return t;
}

}  // namespace

double stability_duration(const SceneDef& scene) {
  return std::ceil((event_time(scene) + 0.5) / scene.h - 1e-9) * scene.h;
}

double quick_stability_duration(const SceneDef& scene) {
  return std::ceil(event_time(scene) / scene.h - 1e-9) * scene.h;
}

}  // namespace invfree
