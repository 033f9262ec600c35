// The scene-file keys as plain data (no TOML types), for documentation and tests:
// docs/scene-keys.md is generated from it (tests/scene_io/scene_keys_doc.cpp) and a test
// keeps the file current. The table itself is scene_io/key_table.cpp.
#pragma once

#include <string>
#include <vector>

namespace invfree {

struct SceneKeyInfo {
  std::string section, key;
  std::string type;   // "number", "integer", "boolean", "string", "[x, y]"
  std::string unit;   // SI, "" when none
  std::string range;  // "> 0", "[0, 0.5)", "1 to 4096"; "" for any finite value or a string
  std::vector<std::string> choices;  // a string key's values
  std::string default_value;         // SceneDef's default, as TOML
  std::string doc;                   // one line
};

struct SceneSectionInfo {
  std::string name;
  bool switches_term;  // the section's presence switches a term on (gravity, ground, ceiling)
  std::string doc;
};

// Every "section.key" a scene file or --set accepts, in table order.
std::vector<std::string> scene_keys();
std::vector<SceneKeyInfo> scene_key_info();
std::vector<SceneSectionInfo> scene_section_info();
// The keys of a [[body]] table (scene_io/body_tables.h); section "body", range from the
// [mesh] or [material] key they stand for, default "" (the scene's value).
std::vector<SceneKeyInfo> body_key_info();

}  // namespace invfree
