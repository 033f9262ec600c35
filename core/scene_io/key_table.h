// The TOML glue of the scene field table (scene/scene_fields.h, the one table of keys,
// types, ranges and docs): a TOML value read into a field, a field written as TOML text.
// Parsing and --set (scene_file.cpp), scene_to_toml, the "unknown key" errors and
// docs/scene-keys.md use it. Private to scene_io: it speaks toml++. Adding a key: one row
// in core/scene/scene_fields.cpp, nothing here.
#pragma once

#include <toml++/toml.h>

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_fields.h"

namespace invfree::scene_io {

using invfree::apply_material;
using invfree::MaterialInput;

// Reads `value` into the scene (or into `material`, for the material keys): the TOML type
// checked, then the field's range. Returns "" or the reason.
std::string read_field(const SceneField& f, SceneDef& scene, MaterialInput& material,
                       const toml::node& value);
// The field's value in the scene as TOML text.
std::string write_field(const SceneField& f, const SceneDef& scene);
// A value as TOML text ("1.0", "4", "true", "\"linear\"", "[0.0, -9.81]").
std::string value_text(const FieldValue& v);

std::vector<std::string> keys_of(std::string_view section);
std::vector<std::string> section_names();

// "a number", "a string", ...: what a value is, for errors.
std::string toml_type_name(const toml::node& value);
// A TOML basic string: quotes, backslashes and control characters escaped.
std::string toml_string(std::string_view text);
// An array of [x, y] into out (Points); an array of those (Loops); "" or the reason.
std::string read_points(const toml::node& value, Loop& out);
std::string read_loops(const toml::node& value, std::vector<Loop>& out);
// A finite number (integer or float) into out; "" or the reason.
std::string read_number(const toml::node& value, double& out);
// [x, y] of finite numbers into out; "" or the reason ("element 0: must be a finite number").
std::string read_vec2(const toml::node& value, Vec2& out);
// An integer key's value into out: a TOML integer, or a number with a whole value (4.0,
// 1e1) below 1e15 in magnitude; the one rule for every integer key, in a section, a
// [[body]] table, a pair of node indices or --set. "" or the reason.
std::string read_int(const toml::node& value, long long& out);
// Why `text` (a --set value TOML could not parse) is no value when it holds a number
// beyond a double's range (1e400, [0, -1e400]): "1e400 is beyond a double's range (about
// 1.8e308): must be a finite number"; "" when it holds none.
std::string unreadable_number(std::string_view text);
// "" when v is within the core's range for `key` ("mesh.side"), else the requirement.
std::string bounds_problem(std::string_view key, double v);

// A double as TOML text that reads back to the same double (shortest round trip, always
// with a '.' or an exponent so that TOML reads a float).
std::string toml_number(double v);

}  // namespace invfree::scene_io
