#include "tests/scene_io/scene_keys_doc.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "scene_io/scene_keys.h"
#include "scene_io/traction_tables.h"

namespace invfree::test {

namespace {

// A default as the docs show it: numbers with at most 6 significant digits ("35714.3"),
// anything else as TOML writes it.
std::string shown(const std::string& toml) {
  char* end = nullptr;
  const double v = std::strtod(toml.c_str(), &end);
  if (toml.empty() || end != toml.c_str() + toml.size()) return "`" + toml + "`";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string range_or_choices(const SceneKeyInfo& k) {
  if (k.choices.empty()) return k.range.empty() && k.type != "boolean" ? "finite" : k.range;
  std::string out;
  for (const auto& c : k.choices) {
    out += out.empty() ? "`\"" : ", `\"";
    out += c;
    out += "\"`";
  }
  return out;
}

// Table cell text: a '|' would end the cell.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string scene_keys_markdown() {
  std::string md = std::string(kSceneKeysBegin) + "\n\n";
  md += "`name` (string): the scene's name; by default the file's name without `.toml`.\n";
  const auto keys = scene_key_info();
  for (const auto& section : scene_section_info()) {
    md += "\n### [" + section.name + "]: " + section.doc + "\n\n";
    md += "| key | type | unit | range or values | default | meaning |\n";
    md += "|---|---|---|---|---|---|\n";
    for (const auto& k : keys) {
      if (k.section != section.name) continue;
      md += "| `" + k.key + "` | " + k.type + " | " + k.unit + " | " + range_or_choices(k) + " | " +
            cell(shown(k.default_value)) + " | " + cell(k.doc) + " |\n";
    }
  }
  md +=
      "\n### [[body]]: one table per body of a scene with several (docs/scenes.md); "
      "none: one body, the [mesh] square at the origin\n\n";
  md += "| key | type | unit | range or values | default | meaning |\n";
  md += "|---|---|---|---|---|---|\n";
  for (const auto& k : body_key_info())
    md += "| `" + k.key + "` | " + k.type + " | " + k.unit + " | " + range_or_choices(k) + " | " +
          (k.default_value.empty() ? "the scene's" : cell(shown(k.default_value))) + " | " +
          cell(k.doc) + " |\n";
  md +=
      "\n### [traction] or [[traction]]: boundary loads (docs/verification.md); none: no "
      "load\n\n";
  md += "| key | type | unit | range or values | default | meaning |\n";
  md += "|---|---|---|---|---|---|\n";
  for (const auto& k : traction_key_info())
    md += "| `" + k.key + "` | " + k.type + " | " + k.unit + " | " + range_or_choices(k) + " | " +
          cell(shown(k.default_value)) + " | " + cell(k.doc) + " |\n";
  return md + "\n" + kSceneKeysEnd + "\n";
}

std::string fuzz_dictionary_block() {
  std::vector<std::string> tokens;
  auto add = [&](const std::string& token) {
    if (std::find(tokens.begin(), tokens.end(), token) == tokens.end()) tokens.push_back(token);
  };
  for (const auto& section : scene_section_info()) add("[" + section.name + "]");
  add("[[body]]");
  add("[[traction]]");
  add("name");
  for (const auto& k : scene_key_info()) add(k.key);
  for (const auto& k : body_key_info()) add(k.key);
  for (const auto& k : traction_key_info()) add(k.key);
  for (const auto& k : scene_key_info())
    for (const auto& c : k.choices) add("\\\"" + c + "\\\"");  // \"c\": a TOML string
  std::string out = std::string(kFuzzDictBegin) + "\n";
  for (const auto& t : tokens) out += "\"" + t + "\"\n";
  return out + kFuzzDictEnd + "\n";
}

std::string generated_block(const std::string& document, const char* begin_marker,
                            const char* end_marker) {
  const size_t begin = document.find(begin_marker);
  const size_t end = document.find(end_marker);
  if (begin == std::string::npos || end == std::string::npos || end < begin) return "";
  const size_t stop = document.find('\n', end);
  return document.substr(begin, (stop == std::string::npos ? document.size() : stop + 1) - begin);
}

}  // namespace invfree::test
