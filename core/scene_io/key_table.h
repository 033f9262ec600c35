// The scene-file keys, one row each: section, key, value type, unit, one-line doc, the
// choices of a string key, and how the value is read into and written from a SceneDef.
// Parsing and --set (scene_file.cpp), scene_to_toml, the "unknown key" errors and
// docs/scene-keys.md all come from this table; a value's range comes from the core
// (scene_value_bounds) and is checked here as the value is read. Private to scene_io: it
// speaks toml++. Adding a key: a SceneDef field, its bounds in core/scene/scene.cpp if it
// has any, one row below (key_table.cpp), then regenerate docs/scene-keys.md.
#pragma once

#include <toml++/toml.h>

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace invfree::scene_io {

// E and nu, or mu and lambda, as read; apply_material turns them into the scene's Lame
// parameters once every key is known (a value given alone keeps the other of its pair).
struct MaterialInput {
  std::optional<double> E, nu, mu, lambda;
};

enum class ValueType { Number, Integer, Boolean, Choice, Vector };
const char* value_type_name(ValueType type);  // as docs/scene-keys.md writes it

struct KeySpec {
  const char* section;
  const char* key;
  ValueType type;
  const char* unit;  // SI, "" when none
  const char* doc;
  std::span<const char* const> choices;  // a Choice's values, as written in TOML
  // Reads `value` into the scene (or into `material`); returns "" or the reason.
  std::string (*read)(const KeySpec& self, SceneDef& scene, MaterialInput& material,
                      const toml::node& value);
  // The value's TOML text.
  std::string (*write)(const SceneDef& scene);
  // False for an input the scene does not keep as such (E and nu: scene_to_toml writes mu
  // and lambda, which give back the very same doubles).
  bool kept = true;

  std::string name() const { return std::string(section) + "." + key; }
};

struct SectionSpec {
  const char* name;
  bool SceneDef::*term;  // switched on by the section's presence; nullptr for none
  const char* doc;
};

std::span<const KeySpec> key_table();
std::span<const SectionSpec> section_table();
const KeySpec* find_key(std::string_view section, std::string_view key);
const SectionSpec* find_section(std::string_view name);
std::vector<std::string> keys_of(std::string_view section);
std::vector<std::string> section_names();

// Sets the scene's Lame parameters from the material keys read. Returns "" or
// "material.<key>: reason" naming a key that was given.
std::string apply_material(SceneDef& scene, const MaterialInput& in);

// "a number", "a string", ...: what a value is, for errors.
std::string toml_type_name(const toml::node& value);
// A finite number (integer or float) into out; "" or the reason.
std::string read_number(const toml::node& value, double& out);
// "" when v is within the core's range for `key` ("mesh.side"), else the requirement.
std::string bounds_problem(std::string_view key, double v);

// A double as TOML text that reads back to the same double (shortest round trip, always
// with a '.' or an exponent so that TOML reads a float).
std::string toml_number(double v);

}  // namespace invfree::scene_io
