// What a scene file leaves out without saying so: a missing [gravity], [ground] or
// [ceiling] section switches that term off, which a student who copied half a scene does
// not expect (a stack floated until the ceiling came). The commands print this note once,
// on stderr, for a scene read from a file (app/scene_options.cpp); the built-in scenes
// leave sections out on purpose and get none.
#pragma once

#include <string>
#include <string_view>

namespace invfree {

// One line, "FILE: no [gravity] section, so gravity is off (...); no [ground]: ...", or ""
// when the text has all three sections (or is not TOML: its errors are load_scene's).
std::string left_out_sections_note(std::string_view toml_text, const std::string& source);
// The same for a file ("" when it cannot be read).
std::string left_out_sections_note_of_file(const std::string& path);

}  // namespace invfree
