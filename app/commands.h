// Each invfree command registers its CLI11 subcommand here; the callback stores the
// command's exit code in `exit_code`.
#pragma once

#include <CLI/CLI.hpp>

namespace invfree {

void register_simulate_command(CLI::App& app, int& exit_code);
void register_bench_command(CLI::App& app, int& exit_code);
void register_render_command(CLI::App& app, int& exit_code);
void register_study_command(CLI::App& app, int& exit_code);
void register_stability_command(CLI::App& app, int& exit_code);
void register_live_command(CLI::App& app, int& exit_code);
void register_inspect_command(CLI::App& app, int& exit_code);
void register_landscape_command(CLI::App& app, int& exit_code);
void register_verify_command(CLI::App& app, int& exit_code);
void register_modes_command(CLI::App& app, int& exit_code);
// Plain `invfree` (no command): the live window when a display is available.
int run_default_command();

}  // namespace invfree
