// Command-line checks shared by the commands. A path option given an empty value
// (`--out ""`) is bad input, reported by the parser as one line with exit code 2, not
// an output that could not be written (4) or an option silently ignored. A number
// option must be finite and in its range: CLI::Range alone lets NaN through (every
// comparison with NaN is false), so `--fps nan` would pass it.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <string>

namespace invfree {

inline CLI::Validator non_empty_path() {
  return CLI::Validator(
      [](const std::string& value) {
        return value.empty() ? std::string("empty path") : std::string();
      },
      "");
}

// A floating-point value in [lo, hi]; NaN and infinities are refused.
inline CLI::Validator finite_range(double lo, double hi) {
  const std::string range =
      "[" + CLI::detail::to_string(lo) + " - " + CLI::detail::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](const std::string& value) {
        char* end = nullptr;
        const double v = std::strtod(value.c_str(), &end);
        if (value.empty() || *end != '\0') return "expected a number, got " + value;
        if (!std::isfinite(v) || v < lo || v > hi) return "value " + value + " not in " + range;
        return std::string();
      },
      "FLOAT in " + range);
}

// `--size WIDTHxHEIGHT` of an offscreen picture ("1280x720", each side 64..8192): "" with
// the size set, or the one-line error.
inline std::string parse_frame_size(const std::string& text, int* width, int* height) {
  static const std::regex pattern("([0-9]{1,5})[xX]([0-9]{1,5})");
  std::smatch m;
  if (std::regex_match(text, m, pattern)) {
    *width = std::stoi(m[1]);
    *height = std::stoi(m[2]);
    if (*width >= 64 && *height >= 64 && *width <= 8192 && *height <= 8192) return "";
  }
  return "--size: expected WIDTHxHEIGHT with each in 64..8192, got \"" + text + "\"";
}

}  // namespace invfree
