// The scenes of assets/scenes/, embedded in the program at build time (the one embedding in
// core/scene_io/CMakeLists.txt), so that no command needs an asset path at run time. They
// are the only definition of every scene: the built-in scenes (compress, drop) that
// `--scene NAME` and the live window's picker offer, and the stress scenes (stress-*.toml)
// of `invfree stability`, which are run from their text and by path.
#pragma once

#include <span>
#include <string_view>

#include "scene_io/scene_file.h"

namespace invfree {

struct EmbeddedScene {
  std::string_view name;  // the file's stem, e.g. "compress"
  std::string_view text;  // the file's TOML text
};

// Every file but the stress scenes, by name.
std::span<const EmbeddedScene> builtin_scenes();
// The stress scenes (stress-*.toml), by name.
std::span<const EmbeddedScene> stress_scene_files();

// A built-in scene, parsed and validated; an error naming the choices when there is none
// of that name.
SceneLoad load_builtin_scene(std::string_view name);
// "compress, drop": the built-in scenes' names, for help texts and errors.
std::string builtin_scene_names();

}  // namespace invfree
