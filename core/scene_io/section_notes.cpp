// The note on a scene file's missing term sections (section_notes.h).
#include "scene_io/section_notes.h"

#include <toml++/toml.h>

#include <fstream>
#include <sstream>

#include "scene_io/error_text.h"
#include "scene_io/toml_guard.h"

namespace invfree {

std::string left_out_sections_note(std::string_view toml_text, const std::string& source) {
  std::string safe_text;
  int line = 0;
  if (!tomlpp_safe_text(toml_text, &safe_text, &line).empty()) return "";
  toml::table root;
  try {
    root = toml::parse(safe_text, source);
  } catch (const toml::parse_error&) {
    return "";
  }
  static constexpr struct {
    const char* section;
    const char* off;
  } kTerms[] = {{"gravity", "gravity is off (Earth's: [gravity] g = [0.0, -9.81])"},
                {"ground", "there is no ground"},
                {"ceiling", "there is no ceiling"}};
  std::string parts;
  for (const auto& t : kTerms) {
    if (root.contains(t.section)) continue;
    parts += std::string(parts.empty() ? "" : "; ") + "no [" + t.section + "] section, so " + t.off;
  }
  if (parts.empty()) return "";
  return printable(source, 200) + ": " + parts +
         " (a section switches its term on; docs/scenes.md)";
}

std::string left_out_sections_note_of_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::ostringstream text;
  text << in.rdbuf();
  return left_out_sections_note(text.str(), path);
}

}  // namespace invfree
