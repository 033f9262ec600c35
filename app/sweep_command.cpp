#include "app/sweep_command.h"

#include <cstdio>
#include <map>

#include "app/command.h"
#include "app/interrupt.h"

namespace invfree {

void add_sweep_options(CLI::App* cmd, SweepCommandOptions& opt, const std::string& out_description,
                       const std::string& quick_description) {
  add_output_directory_option(cmd, opt.out, out_description);
  cmd->add_flag("--quick", opt.quick, quick_description);
  cmd->add_flag("--quiet", opt.quiet, "no progress lines on stderr");
  add_chart_format_option(cmd, opt.format);
  add_force_option(cmd, opt.force, "overwrite the outputs if they exist");
}

CLI::Option* add_chart_format_option(CLI::App* cmd, ChartFormat& format) {
  // A word only (a map-transformer would also take the enum's numbers and print them).
  return cmd
      ->add_option_function<std::string>(
          "--format",
          [&format](const std::string& word) {
            format = word == "svg"   ? ChartFormat::Svg
                     : word == "pdf" ? ChartFormat::Pdf
                                     : ChartFormat::Png;
          },
          "file format of the charts: png, svg or pdf")
      ->type_name("png|svg|pdf")
      ->check(CLI::IsMember({"png", "svg", "pdf"}))
      ->default_str("png");
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
