// Scene files (TOML) and `--set section.key=value` overrides. The keys, their types, units,
// ranges and meaning: docs/scene-keys.md (generated from scene_io/key_table.cpp). In short:
//   name = "..."
//   [mesh] [material] [time] [solver] [initial] [gravity] [ground] [ceiling] [barrier]
// A missing [gravity], [ground] or [ceiling] section switches that term off; in those
// sections `enabled = false` does the same (useful with --set). A file's error reports
// every independent mistake at once, one non-empty line each (joined by '\n', none after
// the last), "<file>:<line>: <section.key>: <reason>": each starts with the file's name and
// names the key the user wrote. An override's error is one line.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "scene/scene.h"
#include "scene_io/scene_keys.h"

namespace invfree {

struct SceneLoad {
  std::optional<SceneDef> scene;
  std::string error;  // set when scene is empty
};

// A built-in scene name (scene_io/builtin_scenes.h), or a path to a TOML file. The result
// is validated.
SceneLoad load_scene(const std::string& name_or_path);
// Parses TOML text; `source` names it in errors. The result is validated.
SceneLoad parse_scene_toml(std::string_view text, const std::string& source);
// Applies "section.key=value" (value in TOML syntax, strings may be unquoted).
// Returns "" on success, otherwise a one-line error; the scene is unchanged then.
std::string apply_override(SceneDef& scene, std::string_view assignment);
// Applies several in order, each value read and checked alone (its type, its key's range),
// then validates the resulting scene once: a scene valid only after several of them
// (fixed.box_min with fixed.box_max, fixed.enabled with fixed.corners) is reached in any
// order. Returns "" or a one-line error naming the --set of the key it blames; the scene is
// unchanged then.
std::string apply_overrides(SceneDef& scene, std::span<const std::string> assignments);
// Serialises a scene as a TOML file that parse_scene_toml reads back to the same scene.
std::string scene_to_toml(const SceneDef& scene);

}  // namespace invfree
