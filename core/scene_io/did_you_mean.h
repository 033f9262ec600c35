// Suggestions for typos: the candidate nearest to a mistyped word (case-insensitive edit
// distance, at most about a third of the word's length), for scene keys and sections,
// built-in scene names, and the command line's options and commands.
// Inputs: the word and the valid words. Outputs: the nearest, or "".
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace invfree {

size_t edit_distance(std::string_view a, std::string_view b);
std::string nearest_word(std::string_view word, const std::vector<std::string>& candidates);
// " (did you mean \"<nearest>\"?)", or "" when nothing is near.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);
// "a, b, c"
std::string join_words(const std::vector<std::string>& words);

}  // namespace invfree
