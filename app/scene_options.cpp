#include "app/scene_options.h"

#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"

namespace invfree {

void SceneOptions::add_to(CLI::App* cmd, const std::string& scene_what,
                          const std::string& set_what) {
  cmd->add_option("--scene", scene, scene_what + " (" + builtin_scene_names() + ") or a TOML scene file")
      ->capture_default_str();
  cmd->add_option("--set", overrides, set_what + ", e.g. --set material.E=1e4 (repeatable)")
      ->type_name("SECTION.KEY=VALUE");
}

std::optional<SceneDef> SceneOptions::resolve(std::string* error) const {
  SceneLoad load = load_scene(scene);
  if (!load.scene) {
    *error = load.error;
    return std::nullopt;
  }
  for (const auto& o : overrides) {
    if (auto e = apply_override(*load.scene, o); !e.empty()) {
      *error = e;
      return std::nullopt;
    }
  }
  return load.scene;
}

std::vector<std::string> SceneOptions::input_files() const {
  for (const auto& e : builtin_scenes())
    if (e.name == scene) return {};  // load_scene prefers the built-in scene of that name
  return {scene};
}

}  // namespace invfree
