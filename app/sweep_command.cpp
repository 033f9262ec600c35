#include "app/sweep_command.h"

#include <cstdio>

#include "app/command.h"
#include "app/interrupt.h"

namespace invfree {

void add_sweep_options(CLI::App* cmd, SweepCommandOptions& opt, const std::string& out_description,
                       const std::string& quick_description) {
  add_output_directory_option(cmd, opt.out, out_description);
  cmd->add_flag("--quick", opt.quick, quick_description);
  cmd->add_flag("--quiet", opt.quiet, "no progress lines on stderr");
}

SweepOptions sweep_options(const SweepCommandOptions& opt, const std::string& name) {
  SweepOptions options;
  options.quick = opt.quick;
  if (!opt.quiet)
    options.progress = [name](const std::string& line) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), line.c_str());
    };
  options.stop = [] { return interrupted(); };
  return options;
}

}  // namespace invfree
