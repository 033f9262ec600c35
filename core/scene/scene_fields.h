// The one table of scene fields: per key of a scene file its section, key, type, unit,
// one-line doc, valid range, default (SceneDef's), whether changing it needs a new mesh,
// the live slider's range where that is deliberately narrower, and how the value is read
// from and written into a SceneDef; the same for the keys of a [[body]] table, and the
// sections. Derived from it: the bounds check (find_scene_problem), needs_new_mesh, the
// scene-file reader and writer (scene_io/key_table.cpp adds only the TOML glue),
// docs/scene-keys.md, the fuzz dictionary's key block (tests/fuzz/scene.dict) and the
// live sliders' ranges (app/live/param_limits.h).
// Adding a key: a SceneDef field and one row in scene_fields.cpp; then regenerate
// docs/scene-keys.md and the dictionary (tests/scene_io/scene_keys_doc_main.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "scene/scene.h"

namespace invfree {

enum class FieldType { Number, Integer, Boolean, Choice, Vector, Text, Points, Loops, Pairs };
// "number", "integer", "boolean", "string", "[x, y]", "path" (a file's, relative to the scene
// file), "[[x, y], ...]" (a polygon), "[[[x, y], ...], ...]" (polygons), "[[i, j], ...]"
// (node index pairs: the springs)
const char* field_type_name(FieldType type);

// A field's value: a Number's double, an Integer's long long (an unsigned field's unsigned
// long long), a Boolean's bool, a Choice's name or a Text, a Vector's Vec2, a Points' Loop,
// Loops' loops, Pairs' index pairs.
using IndexPairs = std::vector<std::array<int, 2>>;
using FieldValue = std::variant<double, long long, unsigned long long, bool, std::string, Vec2,
                                Loop, std::vector<Loop>, IndexPairs>;
double field_number(const FieldValue& v);  // a Number's or Integer's value as a double

// E and nu, or mu and lambda, as read; apply_material turns them into the scene's Lame
// parameters once every key is known (a value given alone keeps the other of its pair).
struct MaterialInput {
  std::optional<double> E, nu, mu, lambda;
};
// Sets the scene's Lame parameters from the material keys read. Returns "" or
// "material.<key>: reason" naming a key that was given.
std::string apply_material(SceneDef& scene, const MaterialInput& in);

// The range of a live slider where it is deliberately narrower than the field's valid range
// (the row says why); lo == hi: the field has no such slider.
struct SliderRange {
  double lo = 0.0, hi = 0.0;
  bool any() const { return lo < hi; }
};

struct SceneField {
  const char* section;
  const char* key;
  FieldType type;
  const char* unit;    // SI, "" when none
  const char* doc;     // one line
  ValueBounds bounds;  // Number and Integer: checked as read and by find_scene_problem
  bool new_mesh;       // a change rebuilds the mesh, the masses or the unknowns
  SliderRange slider;  // the live panel's range, {} for none
  FieldValue (*get)(const SceneDef&);
  // Stores a value of the row's type that is within bounds; "" or why not ("out of
  // range"). nullptr for the material keys, which go through `input` and apply_material.
  std::string (*set)(SceneDef&, const FieldValue&);
  std::optional<double> MaterialInput::*input = nullptr;  // the material keys' slot
  const char* (*choice)(std::size_t i) = nullptr;         // a Choice's i-th name; nullptr after
  bool kept = true;  // false: E and nu, inputs the scene keeps as mu and lambda

  std::string name() const { return std::string(section) + "." + key; }
  std::vector<std::string> choices() const;
};

struct SceneSection {
  const char* name;
  bool SceneDef::*term;  // switched on by the section's presence; nullptr for none
  const char* doc;
};

std::span<const SceneField> scene_fields();
std::span<const SceneSection> scene_sections();
const SceneField* find_scene_field(std::string_view section, std::string_view key);
const SceneField* find_scene_field(std::string_view name);  // "section.key"
const SceneSection* find_scene_section(std::string_view name);

// Checks a value against the row's range and stores it (in `material` for the material
// keys); "" or the reason, the core's wording ("must be a finite number > 0").
std::string assign_field(const SceneField& f, SceneDef& s, MaterialInput& material,
                         const FieldValue& v);

// A key of a [[body]] table. An unset value is the scene's.
struct BodyField {
  const char* key;
  FieldType type;
  const char* unit;
  const char* doc;
  const char* stands_for;  // the scene key whose range it has ("mesh.side"); nullptr: none
  bool new_mesh;           // a change rebuilds the mesh (the material's does not)
  // The body's value, nullopt when unset; nullptr for E and nu (kept as mu and lambda).
  std::optional<FieldValue> (*get)(const BodyDef&);
  void (*set)(BodyDef&, const FieldValue&);  // nullptr for the material keys
  std::optional<double> MaterialInput::*input = nullptr;
  const char* (*choice)(std::size_t i) = nullptr;  // a Choice's i-th name; nullptr after

  std::vector<std::string> choices() const;
};
std::span<const BodyField> body_fields();
const BodyField* find_body_field(std::string_view key);

}  // namespace invfree
