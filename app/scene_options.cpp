#include "app/scene_options.h"

#include <cstdio>
#include <mutex>
#include <set>

#include "scene/scene_fields.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "scene_io/section_notes.h"

namespace invfree {

void SceneOptions::add_to(CLI::App* cmd, const std::string& scene_what,
                          const std::string& set_what) {
  cmd->add_option("--scene", scene,
                  scene_what + " (" + builtin_scene_names() + ") or a TOML scene file")
      ->capture_default_str();
  cmd->add_option("--set", overrides, set_what + ", e.g. --set material.E=1e4 (repeatable)")
      ->type_name("SECTION.KEY=VALUE");
}

namespace {

// "material.E" for "material.E=1e4" (spaces around the name ignored).
std::string override_key(const std::string& assignment) {
  std::string key = assignment.substr(0, assignment.find('='));
  key.erase(0, key.find_first_not_of(" \t"));
  key.erase(key.find_last_not_of(" \t") + 1);
  return key;
}

// The material is given either as E and nu or as mu and lambda, on the command line as in
// a file: mixing them would make the result depend on the order of the --set options.
std::string mixed_material_error(const std::vector<std::string>& overrides) {
  std::string young, lame;
  for (const std::string& o : overrides) {
    const std::string key = override_key(o);
    const SceneField* f = find_scene_field(key);
    if (!f || !f->input) continue;  // the material keys' pairs (scene/scene_fields.h)
    const bool is_young = f->input == &MaterialInput::E || f->input == &MaterialInput::nu;
    std::string& first = is_young ? young : lame;
    if (first.empty()) first = key;
  }
  if (young.empty() || lame.empty()) return "";
  return "--set " + young + " and --set " + lame +
         ": give either E and nu or mu and lambda, not both";
}

// A scene file's missing term sections (section_notes.h), once per file and process on
// stderr: a command that resolves its scene again (study's runs, the live window's
// reload) does not repeat it.
void note_left_out_sections(const std::string& path) {
  static std::mutex mutex;
  static std::set<std::string> noted;
  std::lock_guard lock(mutex);
  if (!noted.insert(path).second) return;
  if (const std::string note = left_out_sections_note_of_file(path); !note.empty())
    std::fprintf(stderr, "invfree: note: %s\n", note.c_str());
}

}  // namespace

std::optional<SceneDef> SceneOptions::resolve(std::string* error) const {
  if (std::string e = mixed_material_error(overrides); !e.empty()) {
    *error = e;
    return std::nullopt;
  }
  SceneLoad load = load_scene(scene);
  if (!load.scene) {
    *error = load.error;
    return std::nullopt;
  }
  if (!input_files().empty()) note_left_out_sections(scene);
  // Each override is read and checked alone (its type and range), the scene they make is
  // validated once (apply_overrides); mesh.shape goes last, so that the keys a shape needs
  // (its outline, file, radius, ...) are in place whichever order they are given.
  auto is_shape = [](const std::string& o) { return o.rfind("mesh.shape=", 0) == 0; };
  std::vector<std::string> ordered;
  for (const bool shape_pass : {false, true})
    for (const auto& o : overrides)
      if (is_shape(o) == shape_pass) ordered.push_back(o);
  if (auto e = apply_overrides(*load.scene, ordered); !e.empty()) {
    *error = e;
    return std::nullopt;
  }
  return load.scene;
}

std::vector<std::string> SceneOptions::input_files() const {
  for (const auto& e : builtin_scenes())
    if (e.name == scene) return {};  // load_scene prefers the built-in scene of that name
  return {scene};
}

}  // namespace invfree
