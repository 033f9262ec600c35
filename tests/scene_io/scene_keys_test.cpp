// The scene field table (core/scene/scene_fields.h) against what is derived from it or must
// agree with it: docs/scene-keys.md, the fuzz dictionary and seeds, the value bounds the
// reader enforces, the choices of string keys, needs_new_mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "scene/scene_fields.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "simulation.h"
#include "tests/scene_io/scene_keys_doc.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

std::string read_source_file(const std::string& relative) {
  std::ifstream in(std::string(::invfree::test::source_dir()) + "/" + relative, std::ios::binary);
  EXPECT_TRUE(in) << relative;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(SceneKeysDoc, MatchesTheParsersKeyTable) {
  const std::string doc = read_source_file("docs/scene-keys.md");
  EXPECT_EQ(test::generated_block(doc), test::scene_keys_markdown())
      << "docs/scene-keys.md is out of date; regenerate its table with\n"
         "  build/release/tests/invfree_scene_keys_doc docs/scene-keys.md";
  for (const auto& key : scene_keys())
    EXPECT_NE(doc.find("| `" + key.substr(key.find('.') + 1) + "` |"), std::string::npos) << key;
}

// The dictionary's generated block is the field table's, as invfree_scene_keys_doc writes it.
TEST(SceneKeysDoc, FuzzDictionaryBlockMatchesTheFieldTable) {
  const std::string dict = read_source_file("tests/fuzz/scene.dict");
  EXPECT_EQ(test::generated_block(dict, test::kFuzzDictBegin, test::kFuzzDictEnd),
            test::fuzz_dictionary_block())
      << "tests/fuzz/scene.dict is out of date; regenerate its block with\n"
         "  build/release/tests/invfree_scene_keys_doc tests/fuzz/scene.dict";
}

// Every section header, key and string value of the table is a token of the fuzz
// dictionary (which also holds TOML syntax and hand-picked values).
TEST(SceneKeysDoc, FuzzDictionaryHasEverySectionKeyAndChoice) {
  std::set<std::string> tokens;
  std::istringstream dict(read_source_file("tests/fuzz/scene.dict"));
  for (std::string line; std::getline(dict, line);)
    if (!line.empty() && line[0] == '"') tokens.insert(line);
  auto expect_token = [&](const std::string& raw) {  // raw as the dictionary writes it
    EXPECT_TRUE(tokens.count("\"" + raw + "\"")) << "tests/fuzz/scene.dict lacks \"" << raw << "\"";
  };
  for (const auto& s : scene_section_info()) expect_token("[" + s.name + "]");
  for (const auto& k : scene_key_info()) {
    expect_token(k.key);
    for (const auto& c : k.choices) expect_token("\\\"" + c + "\\\"");
  }
  expect_token("name");
}

// Together, the seed inputs of tests/fuzz/corpus/ use every key (in a file or in --set).
TEST(SceneKeysDoc, FuzzSeedsUseEveryKey) {
  std::set<std::string> used;
  const std::string dir = std::string(::invfree::test::source_dir()) + "/tests/fuzz/corpus";
  for (const auto& f : std::filesystem::directory_iterator(dir)) {
    if (f.path().filename().string().rfind("seed_", 0) != 0) continue;
    std::ifstream in(f.path());
    std::string section;
    bool overrides = false;
    for (std::string line; std::getline(in, line);) {
      if (line == "%%") overrides = true;
      const size_t eq = line.find('=');
      if (!overrides && line.size() > 2 && line[0] == '[') {
        section = line.substr(1, line.find(']') - 1);
      } else if (eq != std::string::npos) {
        std::string key = line.substr(0, eq);
        key.erase(key.find_last_not_of(' ') + 1);
        used.insert(overrides || key.find('.') != std::string::npos ? key : section + "." + key);
      }
    }
  }
  for (const auto& key : scene_keys())
    EXPECT_TRUE(used.count(key)) << key << " is in no tests/fuzz/corpus/seed_* input";
}

// The core's bounds (scene_value_bounds) name scene keys, and the reader enforces each
// bound at the key the user wrote, with the core's wording.
TEST(SceneKeys, EveryBoundIsAKeyAndIsEnforcedWhereItIsRead) {
  const auto keys = scene_keys();
  const SceneDef base = *load_builtin_scene("compress").scene;
  for (const auto& v : scene_value_bounds()) {
    EXPECT_NE(std::find(keys.begin(), keys.end(), v.key), keys.end()) << v.key;
    const ValueBounds& b = v.bounds;
    std::vector<double> outside;
    const double step = b.integer ? 1.0 : 1e-9;
    if (std::isfinite(b.lo)) outside.push_back(b.lo_open ? b.lo : b.lo - step);
    if (std::isfinite(b.hi)) outside.push_back(b.hi_open ? b.hi : b.hi + step);
    for (double x : outside) {
      char value[64];
      std::snprintf(value, sizeof value, b.integer ? "%.0f" : "%.17g", x);
      SceneDef s = base;
      const std::string assignment = std::string(v.key) + "=" + value;
      EXPECT_NE(apply_override(s, assignment).find(std::string(v.key) + ": " + b.requirement()),
                std::string::npos)
          << assignment << ": " << apply_override(s, assignment);
      const std::string section = std::string(v.key).substr(0, std::string(v.key).find('.'));
      const std::string key = std::string(v.key).substr(section.size() + 1);
      const SceneLoad load =
          parse_scene_toml("[" + section + "]\n" + key + " = " + value + "\n", "b.toml");
      EXPECT_NE(load.error.find("b.toml:2: " + std::string(v.key) + ": " + b.requirement()),
                std::string::npos)
          << load.error;
    }
  }
}

TEST(SceneKeys, EveryChoiceReadsAndWritesBack) {
  const SceneDef base = *load_builtin_scene("compress").scene;
  for (const auto& k : scene_key_info()) {
    for (const auto& c : k.choices) {
      SceneDef s = base;
      if (k.key == "model" && c != "neo-hookean") s.jitter = 0.0;
      if (k.section == "fixed") {  // a box holding a node: "none" then selects that one
        s.fixed_box_min = s.fixed_box_max = Vec2(-0.5, -0.5);
      }
      if (c == "static") {  // held against rigid motion: the bottom edge fixed, no planes
        s.has_fixed = true;
        s.fixed_corners = FixedCorners::Bottom;
        s.has_ground = s.has_ceiling = false;
      }
      if (k.section == "reduced") s.has_ceiling = false;  // a basis has no ceiling unknown
      // A polygon needs its outline; svg and mesh a file (tests/simulation/shape_scene_test).
      if (k.key == "shape" && (c == "svg" || c == "mesh")) continue;
      if (k.key == "shape") s.shape.outline = {Vec2(-0.5, -0.5), Vec2(0.5, -0.5), Vec2(0.0, 0.5)};
      if (k.key == "shape" && c == "points") {  // particles: their masses and springs
        s.shape.points = {Vec2(0.0, 0.0), Vec2(0.1, 0.0)};
        s.node_mass = 1.0;
        s.has_mass_spring = true;
      }
      EXPECT_EQ(apply_override(s, k.section + "." + k.key + "=" + c), "") << c;
      EXPECT_NE(scene_to_toml(s).find("\n" + k.key + " = \"" + c + "\"\n"), std::string::npos)
          << c << "\n"
          << scene_to_toml(s);
    }
  }
}

// A value of the field's type other than `v` (not necessarily a valid one).
FieldValue other_value(const SceneField& f, const FieldValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return *d + 1.0;
  if (const auto* i = std::get_if<long long>(&v)) return *i + 1;
  if (const auto* u = std::get_if<unsigned long long>(&v)) return static_cast<long long>(*u + 1);
  if (const auto* b = std::get_if<bool>(&v)) return !*b;
  if (const auto* c = std::get_if<std::string>(&v)) {
    if (f.type == FieldType::Text) return *c + "x";
    for (const auto& name : f.choices())
      if (name != *c) return name;
  }
  if (const auto* loop = std::get_if<Loop>(&v)) {
    Loop other = *loop;
    other.push_back(Vec2(1.0, 2.0));
    return other;
  }
  if (const auto* loops = std::get_if<std::vector<Loop>>(&v)) {
    std::vector<Loop> other = *loops;
    other.push_back(Loop{Vec2(1.0, 2.0)});
    return other;
  }
  if (const auto* pairs = std::get_if<IndexPairs>(&v)) {
    IndexPairs other = *pairs;
    other.push_back({0, 1});
    return other;
  }
  return Vec2(std::get<Vec2>(v) + Vec2(1.0, 1.0));
}

// needs_new_mesh is the table's column: changing one field rebuilds exactly when its row says
// so, and the rows that say so are the mesh, the masses and the unknowns (the ceiling's).
TEST(SceneKeys, NeedsNewMeshIsTheTablesColumn) {
  const SceneDef base = *load_builtin_scene("compress").scene;
  std::set<std::string> rebuilding;
  for (const SceneField& f : scene_fields()) {
    SceneDef next = base;
    if (f.set) {
      ASSERT_EQ(f.set(next, other_value(f, f.get(base))), "") << f.name();
    } else if (f.kept) {  // mu, lambda
      next.lame = {base.lame.mu * 2.0, base.lame.lambda * 2.0};
    } else {
      continue;
    }
    EXPECT_EQ(needs_new_mesh(base, next), f.new_mesh) << f.name();
    if (f.new_mesh) rebuilding.insert(f.name());
  }
  EXPECT_EQ(rebuilding,
            (std::set<std::string>{
                "mesh.side",     "mesh.n_seg",      "mesh.density",        "mesh.mass",
                "mesh.jitter",   "mesh.seed",       "mesh.shape",          "mesh.width",
                "mesh.height",   "mesh.radius",     "mesh.inner_radius",   "mesh.outline",
                "mesh.holes",    "mesh.file",       "mesh.path_id",        "mesh.scale",
                "mesh.max_edge", "ceiling.enabled", "mass_spring.enabled", "fixed.enabled",
                "fixed.corners", "fixed.box_min",   "fixed.box_max",       "fixed.boxes",
                "fixed.components", "fixed.x_boxes", "fixed.y_boxes",   "mesh.node_mass",
                "mesh.points",   "mass_spring.springs", "reduced.basis",  "reduced.order",
                "reduced.modes"}));
  // [[body]]: a body more or fewer, or its square, place or velocity; not its material.
  SceneDef two = base;
  two.bodies = {BodyDef{}, BodyDef{}};
  two.bodies[1].offset = Vec2(2.0, 0.0);
  EXPECT_TRUE(needs_new_mesh(base, two));
  SceneDef changed = two;
  changed.bodies[0].lame = Lame{1e4, 1e4};
  EXPECT_FALSE(needs_new_mesh(two, changed));
  for (const BodyField& f : body_fields()) {
    if (!f.set) continue;
    changed = two;
    FieldValue value = Vec2(3.0, 1.0);
    if (f.type == FieldType::Integer) value = 7LL;
    if (f.type == FieldType::Number) value = 0.5;
    if (f.type == FieldType::Choice) value = f.choices().back();
    if (f.type == FieldType::Text) value = std::string("x.svg");
    if (f.type == FieldType::Points) value = Loop{Vec2(0.0, 0.0), Vec2(1.0, 0.0), Vec2(0.0, 1.0)};
    if (f.type == FieldType::Loops) value = std::vector<Loop>{Loop{Vec2(0.1, 0.1)}};
    f.set(changed.bodies[1], value);
    EXPECT_EQ(needs_new_mesh(two, changed), f.new_mesh) << f.key;
    EXPECT_TRUE(f.new_mesh) << f.key;
  }
}

}  // namespace
}  // namespace invfree
