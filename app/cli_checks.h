// Command-line checks shared by the commands. A path option given an empty value
// (`--out ""`) is bad input, reported by the parser as one line with exit code 2, not
// an output that could not be written (4) or an option silently ignored.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace invfree {

inline CLI::Validator non_empty_path() {
  return CLI::Validator(
      [](const std::string& value) {
        return value.empty() ? std::string("empty path") : std::string();
      },
      "");
}

}  // namespace invfree
