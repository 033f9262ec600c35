// The [traction] table or [[traction]] tables of a scene file (scene.h's TractionDef,
// scene/tractions.h): keys box_min, box_max, force, pressure; read into SceneDef::tractions
// and written back by scene_to_toml as [[traction]] tables. Private to scene_io.
#pragma once

#include <toml++/toml.h>

#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene_io/scene_keys.h"

namespace invfree::scene_io {

struct TractionError {
  int line = 0;
  std::string message;  // "" when nothing went wrong; names the key as "traction.<key>"
};
// Reads the `traction` node: one table, or an array of tables.
TractionError read_traction_tables(const toml::node& node, std::vector<TractionDef>& out);
std::string traction_tables_to_toml(const SceneDef& scene);
std::vector<std::string> traction_keys();

}  // namespace invfree::scene_io

namespace invfree {
// The keys of a [[traction]] table, for docs/scene-keys.md (section "traction").
std::vector<SceneKeyInfo> traction_key_info();
}  // namespace invfree
