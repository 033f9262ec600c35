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
  static const std::map<std::string, ChartFormat> formats = {
      {"png", ChartFormat::Png}, {"svg", ChartFormat::Svg}, {"pdf", ChartFormat::Pdf}};
  return cmd->add_option("--format", format, "file format of the charts: png, svg or pdf")
      ->type_name("FORMAT")
      ->transform(CLI::CheckedTransformer(formats))
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
