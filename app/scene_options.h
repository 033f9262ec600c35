// The scene options every command shares: --scene NAME|FILE and repeated --set
// section.key=value. `resolve` loads the scene, applies the overrides in order and
// validates; on failure it returns an empty optional and a one-line error. `input_files`
// names the file the command reads (none for a built-in scene), which no output may be.
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

  void add_to(CLI::App* cmd);
  std::optional<SceneDef> resolve(std::string* error) const;
  std::vector<std::string> input_files() const;
};

}  // namespace invfree
