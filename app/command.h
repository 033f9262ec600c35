// The skeleton every invfree command shares. A command is a plain options struct, a
// `run` function from the options to an exit code (exit_codes.h), and a register function
// that adds the CLI11 subcommand with add_command and then its options. Failures are
// reported by `fail` as one line "invfree: <message>" on stderr.
#pragma once

#include <CLI/CLI.hpp>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "app/output_files.h"

namespace invfree {

// Prints "invfree: <message>" on stderr; returns `code`.
int fail(int code, const std::string& message);

// A registered subcommand and the options its callback will run with.
template <class Options>
struct Command {
  CLI::App* cmd;
  Options& opt;
};

// Adds the subcommand `name`; when the command line selects it, `exit_code = run(opt)`
// with the options parsed into `opt` (owned by the callback, alive as long as `app`).
template <class Options, class Run>
Command<Options> add_command(CLI::App& app, int& exit_code, const std::string& name,
                             const std::string& description, Run run) {
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(name, description);
  cmd->callback([opt, &exit_code, run] { exit_code = run(*opt); });
  return {cmd, *opt};
}

// --out DIR: the directory a command writes into (default shown in --help; never empty).
CLI::Option* add_output_directory_option(CLI::App* cmd, std::string& dir,
                                         const std::string& description);

// Checks, before a long run, that every one of `paths` can be written and is none of the
// run's `inputs` (check_output_file). Returns the first error (exit code and one line),
// or none.
OutputError check_output_files(std::initializer_list<std::string> paths,
                               const std::vector<std::string>& inputs = {});
// The same, and the rule every output follows (docs/outputs.md): a file that exists
// already is refused (exit_code::kBadInput, "... exists; use --force to overwrite it")
// unless `force`.
OutputError check_output_files(std::initializer_list<std::string> paths,
                               const std::vector<std::string>& inputs, bool force);

// --force: the flag that allows a command to replace its existing outputs.
CLI::Option* add_force_option(CLI::App* cmd, bool& force, const std::string& description);

}  // namespace invfree
