// The [[body]] tables of a scene file: an array of tables, one per body, with the keys of
// scene/scene_fields.h's body_fields() (side, n_seg, offset, velocity, E and nu or mu and
// lambda), read into SceneDef::bodies (scene/scene.h) and written back by scene_to_toml.
// Private to scene_io: it speaks toml++.
#pragma once

#include <toml++/toml.h>

#include <span>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene_io/key_table.h"

namespace invfree::scene_io {

// A body as read, before the scene's own material is known.
struct BodyInput {
  BodyDef body;
  MaterialInput material;
  int line = 0;  // the table's line, for errors about the body as a whole
  std::vector<std::pair<std::string, int>> key_lines;  // each key given and its line
};

// What went wrong where: "" when nothing did.
struct BodyError {
  int line = 0;
  std::string message;  // names the key as "body.<key>" and the table's number (1-based)
};
// Reads the `body` node (must be an array of tables).
BodyError read_body_tables(const toml::node& node, std::vector<BodyInput>& out);
// Sets each body's own material, if it gave one, from the scene's (already applied)
// [material]: a value given alone keeps the other of its pair, as in [material].
std::string apply_body_materials(SceneDef& scene, std::span<const BodyInput> in, int* line);
// The [[body]] tables of the scene, "" for a scene without.
std::string body_tables_to_toml(const SceneDef& scene);
// The keys of a [[body]] table, for errors and docs.
std::vector<std::string> body_keys();

}  // namespace invfree::scene_io
