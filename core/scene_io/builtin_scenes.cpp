#include "scene_io/builtin_scenes.h"

#include <string>

#include "scene_io/error_text.h"

namespace invfree {

// Generated into the build directory by core/scene_io/CMakeLists.txt.
extern const EmbeddedScene kEmbeddedBuiltinScenes[];
extern const std::size_t kEmbeddedBuiltinSceneCount;
extern const EmbeddedScene kEmbeddedStressScenes[];
extern const std::size_t kEmbeddedStressSceneCount;

std::span<const EmbeddedScene> builtin_scenes() {
  return {kEmbeddedBuiltinScenes, kEmbeddedBuiltinSceneCount};
}

std::span<const EmbeddedScene> stress_scene_files() {
  return {kEmbeddedStressScenes, kEmbeddedStressSceneCount};
}

SceneLoad load_builtin_scene(std::string_view name) {
  for (const auto& e : builtin_scenes())
    if (e.name == name)
      return parse_scene_toml(e.text, "assets/scenes/" + std::string(e.name) + ".toml");
  return {std::nullopt, printable(name) + ": not a built-in scene (" + builtin_scene_names() + ")"};
}

std::string builtin_scene_names() {
  std::string names;
  for (const auto& e : builtin_scenes()) (names += names.empty() ? "" : ", ") += e.name;
  return names;
}

}  // namespace invfree
