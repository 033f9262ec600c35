// Suggestions for a command line CLI11 refused: for each unexpected word, the nearest
// option of the command it was given to ("--stpes" -> "--steps") or, when no command was
// selected, the nearest command ("simulat" -> "simulate"; scene_io/did_you_mean.h).
// Inputs: the app after a failed parse. Output: " (did you mean ...?)" text, or "".
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace invfree {

std::string cli_suggestions(CLI::App& app);

}  // namespace invfree
