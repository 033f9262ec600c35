// A guard in front of toml++ 3.3 (Debian 12): rewrites or refuses scene text that would
// make toml++ misbehave, before toml++ sees it. Valid TOML keeps its meaning.
//  - Unsafe code points. toml++ 3.3.0 reaches __builtin_unreachable() -- undefined
//    behaviour, found by our fuzzer -- when it asks whether a code point in U+00A1..U+0499,
//    U+2C8E..U+3087 (but U+3000) or U+FB26..U+FEFE is whitespace (upstream issues #190 and
//    #295); its parser asks that of characters outside strings, after a backslash in a
//    string, and while reporting some errors. In a basic string such a code point becomes
//    the equivalent \uXXXX escape, a literal string holding one is rewritten as the
//    equivalent basic string, in a comment it becomes '?', and anywhere else (where no
//    valid scene has a non-ASCII character) the text is refused.
//  - Deep dotted keys. toml++ recurses once per part of a dotted key (`a.b.c = 1`,
//    `[a.b.c]`, `[[a.b.c]]`) and overflows the stack at about 40,000 parts. A scene needs
//    two levels (section.key), so a dotted run of more than two parts outside strings and
//    comments is refused; no valid TOML value has one (a float or a time has one dot).
// Bracket and brace nesting needs no guard: toml++ limits it itself.
#pragma once

#include <string>
#include <string_view>

namespace invfree {

// Returns "" and the text for toml++ in *out, or a reason (one line) and its line in *line.
std::string tomlpp_safe_text(std::string_view text, std::string* out, int* line);

}  // namespace invfree
