// invfree: the command-line entry point. Each command lives in its own file and
// registers itself in commands.h. Around every command: the signal handlers first
// (app/interrupt.h), INVFREE_THREADS (checked, then given to the core), and after it the
// check that standard output (the summary line) was written.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>
#include <system_error>

#include "app/cli_suggestions.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/output_files.h"
#include "app/process_limits.h"
#include "linalg/parallel.h"
#include "solver/newton_interrupt.h"

namespace {

// INVFREE_THREADS: the core's worker threads (core/linalg/parallel.h), a whole number
// from 1 to 256 when set and not empty. `threads` 0 (unset or empty) means every core.
struct ThreadVariable {
  int threads = 0;
  std::string error;  // "" or a one-line error
};

ThreadVariable read_thread_variable() {
  const char* value = std::getenv("INVFREE_THREADS");
  if (value == nullptr || *value == '\0') return {};
  const std::string text = value;
  const bool digits = text.size() <= 3 && text.find_first_not_of("0123456789") == std::string::npos;
  if (digits && std::atoi(value) >= 1 && std::atoi(value) <= 256) return {std::atoi(value), ""};
  std::string shown = text.substr(0, 40);
  for (char& c : shown)
    if (c < ' ' || c == 127) c = '?';
  return {0, "INVFREE_THREADS=\"" + shown + (text.size() > 40 ? "...\"" : "\"") +
                 ": expected a whole number from 1 to 256 (or unset it to use every core)"};
}

}  // namespace

int main(int argc, char** argv) {
  invfree::prepare_for_resource_limits(argv);  // first: may execute the program again
  invfree::install_interrupt_handlers();
  invfree::set_newton_interrupt_check(&invfree::interrupted);  // one long step stops too
  CLI::App app{
      "invfree: inversion-free neo-Hookean elastodynamics of a soft square (lecture 9, "
      "\"Stress and Its Derivative\").\n"
      "Exit codes: 0 ok, 2 bad input (command line, scene file, --set), 3 a step failed "
      "(Newton cap, non-finite values, broken invariant), 4 an output could not be written, "
      "129 hang-up (SIGHUP), 130 interrupted (Ctrl-C, SIGTERM); outputs: docs/outputs.md."};
  app.require_subcommand(0, 1);  // none: the live window (app/live_command.cpp)
  app.set_help_all_flag("--help-all", "show help for every command");
  app.set_version_flag("--version", "invfree " INVFREE_VERSION);
  // After parsing (so --help still works), before any command runs.
  app.parse_complete_callback([] {
    const ThreadVariable threads = read_thread_variable();
    if (!threads.error.empty()) throw CLI::ValidationError(threads.error);
    invfree::set_thread_count(threads.threads);
  });
  int exit_code = invfree::exit_code::kOk;
  invfree::register_simulate_command(app, exit_code);
  invfree::register_bench_command(app, exit_code);
  invfree::register_render_command(app, exit_code);
  invfree::register_study_command(app, exit_code);
  invfree::register_stability_command(app, exit_code);
  invfree::register_live_command(app, exit_code);
  invfree::register_inspect_command(app, exit_code);
  invfree::register_landscape_command(app, exit_code);
  invfree::register_verify_command(app, exit_code);
  invfree::register_modes_command(app, exit_code);
  try {
    app.parse(argc, argv);  // runs the command
    if (app.get_subcommands().empty()) exit_code = invfree::run_default_command();
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // May quote the user's text: keep the error on one line.
    std::string what = e.what() + invfree::cli_suggestions(app);
    for (char& c : what)
      if (c == '\n' || c == '\r') c = ' ';
    std::fprintf(stderr, "invfree: %s (see invfree --help)\n", what.c_str());
    return invfree::exit_code::kBadInput;
  } catch (const std::bad_alloc&) {  // never an exception trace or an abort
    std::fprintf(stderr, "invfree: out of memory\n");
    return invfree::exit_code::kRunFailed;
  } catch (const std::system_error& e) {  // std::thread: no thread could be made
    if (e.code() != std::errc::resource_unavailable_try_again) {
      std::fprintf(stderr, "invfree: internal error: %s\n", e.what());
      return invfree::exit_code::kRunFailed;
    }
    std::fprintf(stderr,
                 "invfree: cannot start a thread: %s (a process-count or memory limit: ulimit "
                 "-u, -v)\n",
                 e.code().message().c_str());
    return invfree::exit_code::kRunFailed;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "invfree: internal error: %s\n", e.what());
    return invfree::exit_code::kRunFailed;
  }
  const std::string stdout_error = invfree::standard_output_error();
  if (!stdout_error.empty() && exit_code == invfree::exit_code::kOk) {
    std::fprintf(stderr, "invfree: %s\n", stdout_error.c_str());
    return invfree::exit_code::kOutputFailed;
  }
  return exit_code;
}
