#include "scene/scene.h"

#include <cmath>

#include "scene/initial_state.h"

namespace invfree {

namespace {

SceneDef make_compress() {
  return SceneDef{};
}

SceneDef make_drop() {
  SceneDef s;
  s.name = "drop";
  s.has_ceiling = false;
  s.friction = 0.0;
  return s;
}

constexpr SceneEntry kScenes[] = {
    {"compress", "the reference demo: a soft square drops on the ground and a ceiling squashes it",
     make_compress},
    {"drop", "the same square falling on a frictionless ground, no ceiling", make_drop},
};

}  // namespace

const char* integrator_name(Integrator i) {
  return i == Integrator::ImplicitEuler ? "implicit-euler" : "symplectic-euler";
}

std::optional<Integrator> integrator_from_name(std::string_view name) {
  if (name == "implicit-euler") return Integrator::ImplicitEuler;
  if (name == "symplectic-euler") return Integrator::SymplecticEuler;
  return std::nullopt;
}

std::span<const SceneEntry> builtin_scenes() {
  return kScenes;
}

std::optional<SceneDef> find_builtin_scene(std::string_view name) {
  for (const auto& e : kScenes)
    if (name == e.name) return e.make();
  return std::nullopt;
}

std::string validate_scene(const SceneDef& s) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  // Ranges first, whether or not the term that uses a value is switched on: a bad value
  // stays bad when a later --set switches its term on, and a student learns of it at once.
  if (!positive(s.side)) return "mesh.side: must be a finite number > 0";
  if (s.n_seg < 1) return "mesh.n_seg: must be an integer >= 1";
  if (s.n_seg > kMaxSegments)
    return "mesh.n_seg: at most " + std::to_string(kMaxSegments) +
           " (the mesh would not fit in memory)";
  if (auto e = check_mesh_fits_in_memory(s.n_seg); !e.empty()) return "mesh.n_seg: " + e;
  if (!positive(s.density)) return "mesh.density: must be a finite number > 0";
  if (!(std::isfinite(s.jitter) && s.jitter >= 0.0 && s.jitter < 0.5))
    return "mesh.jitter: must be in [0, 0.5)";
  if (!positive(s.lame.mu)) return "material.mu: must be a finite number > 0 (E > 0)";
  if (!(std::isfinite(s.lame.lambda) && s.lame.lambda >= 0.0))
    return "material.lambda: must be a finite number >= 0 (nu in [0, 0.5))";
  if (!positive(s.h)) return "time.h: must be a finite number > 0";
  if (!positive(s.tol)) return "time.tol: must be a finite number > 0";
  if (s.max_newton < 1) return "time.max_newton: must be an integer >= 1";
  if (!s.initial_velocity.allFinite()) return "initial.velocity: must be finite";
  if (!s.gravity.allFinite()) return "gravity.g: must be finite";
  if (!std::isfinite(s.ground_y)) return "ground.y: must be finite";
  if (!(std::isfinite(s.friction) && s.friction >= 0.0))
    return "ground.friction: must be a finite number >= 0";
  if (!std::isfinite(s.ceiling_y)) return "ceiling.y: must be finite";
  if (!std::isfinite(s.ceiling_velocity)) return "ceiling.velocity: must be finite";
  if (!std::isfinite(s.ceiling_stop)) return "ceiling.stop: must be finite";
  if (!positive(s.dhat)) return "barrier.dhat: must be a finite number > 0";
  if (!positive(s.kappa)) return "barrier.kappa: must be a finite number > 0";
  // Relations between switched-on terms.
  if (s.has_ceiling && s.has_ground) {
    if (s.ceiling_y <= s.ground_y) return "ceiling.y: must be above ground.y";
    if (s.ceiling_stop <= s.ground_y) return "ceiling.stop: must be above ground.y";
  }
  return check_initial_state(s);
}

}  // namespace invfree
