// What the sweep commands (`invfree study`, `invfree stability`) share on the command
// line: --out DIR, --quick, --quiet, --format png|svg|pdf (the charts) and --force, and
// the SweepOptions they give the sweep (progress lines on stderr, a stop on Ctrl-C).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "app/plot/canvas.h"
#include "app/study/sweep_options.h"

namespace invfree {

struct SweepCommandOptions {
  std::string out = ".";
  bool quick = false;
  bool quiet = false;
  bool force = false;
  ChartFormat format = ChartFormat::Png;
};

// --format png|svg|pdf: the file format of a command's charts.
CLI::Option* add_chart_format_option(CLI::App* cmd, ChartFormat& format);

void add_sweep_options(CLI::App* cmd, SweepCommandOptions& opt, const std::string& out_description,
                       const std::string& quick_description);

// quick from --quick; progress "<name>: <line>" on stderr unless --quiet; stop once Ctrl-C
// arrived (interrupt.h: the handlers are installed in main).
SweepOptions sweep_options(const SweepCommandOptions& opt, const std::string& name);

}  // namespace invfree
