// User text quoted in scene_io's one-line errors: control characters escaped and long
// text cut (printable), string values in double quotes (quoted).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace invfree {

// Control characters escaped (\n, \t, \xNN) and text beyond max_chars cut with "...",
// never inside a UTF-8 sequence, so every error stays one readable line.
std::string printable(std::string_view text, std::size_t max_chars = 80);
// A user's string value in double quotes, with quotes and backslashes escaped.
std::string quoted(std::string_view text);
bool has_control_characters(std::string_view text);

}  // namespace invfree
