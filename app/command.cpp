#include "app/command.h"

#include <cstdio>

#include "app/cli_checks.h"
#include "app/output_files.h"

namespace invfree {

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "invfree: %s\n", message.c_str());
  return code;
}

CLI::Option* add_output_directory_option(CLI::App* cmd, std::string& dir,
                                         const std::string& description) {
  return cmd->add_option("--out", dir, description)
      ->type_name("DIR")
      ->capture_default_str()
      ->check(non_empty_path());
}

OutputError check_output_files(std::initializer_list<std::string> paths,
                               const std::vector<std::string>& inputs) {
  for (const std::string& p : paths)
    if (OutputError e = check_output_file(p, inputs)) return e;
  return {};
}

}  // namespace invfree
