// invfree: the command-line entry point. Each command lives in its own file and
// registers itself in commands.h.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <new>
#include <string>

#include "app/commands.h"
#include "app/exit_codes.h"

int main(int argc, char** argv) {
  CLI::App app{
      "invfree: inversion-free neo-Hookean elastodynamics of a soft square (lecture 9, "
      "\"Stress and Its Derivative\").\n"
      "Exit codes: 0 ok, 2 bad input (command line, scene file, --set), 3 a step failed "
      "(Newton cap, non-finite values, broken invariant), 4 an output could not be written, "
      "130 interrupted."};
  app.require_subcommand(0, 1);  // none: the live window (app/live_command.cpp)
  app.set_help_all_flag("--help-all", "show help for every command");
  int exit_code = invfree::exit_code::kOk;
  invfree::register_simulate_command(app, exit_code);
  invfree::register_bench_command(app, exit_code);
  invfree::register_render_command(app, exit_code);
  invfree::register_study_command(app, exit_code);
  invfree::register_stability_command(app, exit_code);
  invfree::register_live_command(app, exit_code);
  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) return invfree::run_default_command();
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();  // may quote the user's text: keep the error on one line
    for (char& c : what)
      if (c == '\n' || c == '\r') c = ' ';
    std::fprintf(stderr, "invfree: %s (see invfree --help)\n", what.c_str());
    return invfree::exit_code::kBadInput;
  } catch (const std::bad_alloc&) {  // never an exception trace or an abort
    std::fprintf(stderr, "invfree: out of memory\n");
    return invfree::exit_code::kRunFailed;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "invfree: internal error: %s\n", e.what());
    return invfree::exit_code::kRunFailed;
  }
  return exit_code;
}
