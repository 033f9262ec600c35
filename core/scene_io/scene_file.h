// Scene files (TOML) and `--set section.key=value` overrides, on top of the built-in
// scene table. Sections and keys:
//   name = "..."
//   [mesh]     side, n_seg, density, mass ("uniform" | "lumped"), jitter, seed
//   [material] model ("neo-hookean" | "linear" | "arap" | "stable-neo-hookean"),
//              E, nu  -- or --  mu, lambda
//   [time]     h, tol, max_newton
//   [solver]   projection ("diagonal" | "full" | "none"), inversion_filter,
//              integrator ("implicit-euler" | "symplectic-euler"),
//              linear_solver ("auto" | "ldlt" | "cholmod" | "pcg"),
//              step_expansion, friction_crossing_stop (Newton's safeguards, core/newton.h)
//   [initial]  velocity = [vx, vy]
//   [gravity]  g = [gx, gy]
//   [ground]   y, friction
//   [ceiling]  y, velocity, stop
//   [barrier]  dhat, kappa
// A missing [gravity], [ground] or [ceiling] section switches that term off; in those
// sections `enabled = false` does the same (useful with --set). Every error is one line:
// "<file>:<line>: <section.key>: <reason>".
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace invfree {

struct SceneLoad {
  std::optional<SceneDef> scene;
  std::string error;  // set when scene is empty
};

// A built-in scene name, or a path to a TOML file. The result is validated.
SceneLoad load_scene(const std::string& name_or_path);
// Parses TOML text; `source` names it in errors. The result is not yet validated.
SceneLoad parse_scene_toml(std::string_view text, const std::string& source);
// Applies "section.key=value" (value in TOML syntax, strings may be unquoted).
// Returns "" on success, otherwise a one-line error.
std::string apply_override(SceneDef& scene, std::string_view assignment);
// Every "section.key" a scene file or --set accepts, in table order (tests, fuzz dictionary).
std::vector<std::string> scene_keys();
// Serialises a scene as a TOML file that parse_scene_toml reads back to the same scene.
std::string scene_to_toml(const SceneDef& scene);

}  // namespace invfree
