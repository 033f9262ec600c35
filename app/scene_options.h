// The scene options every command shares: --scene NAME|FILE and repeated --set
// section.key=value. `resolve` loads the scene and applies the overrides in order (mesh.shape
// last, after the keys a shape reads), each read alone, the scene they make validated once
// (scene_io/scene_file.h's apply_overrides); on failure it
// returns an empty optional and a one-line error. As in a scene file, E/nu and mu/lambda cannot be
// mixed: --set material.E (or nu) together with --set material.mu (or lambda) is an error.
// `input_files` names the file the command reads (none for a built-in scene), which no output may
// be.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace invfree {

struct SceneOptions {
  std::string scene = "compress";
  std::vector<std::string> overrides;

  // `scene_what` and `set_what` begin the options' help ("<scene_what> (<built-in names>)
  // or a TOML scene file", "<set_what>, e.g. --set material.E=1e4 (repeatable)").
  void add_to(CLI::App* cmd, const std::string& scene_what = "built-in scene",
              const std::string& set_what = "override a scene value");
  std::optional<SceneDef> resolve(std::string* error) const;
  std::vector<std::string> input_files() const;
};

}  // namespace invfree
