#include "app/command.h"

#include <cstdio>
#include <filesystem>

#include "app/cli_checks.h"
#include "app/exit_codes.h"
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

OutputError check_output_files(std::initializer_list<std::string> paths,
                               const std::vector<std::string>& inputs, bool force) {
  // The rules of check_output_file first: they say more about a target that is no file.
  if (OutputError e = check_output_files(paths, inputs)) return e;
  if (!force)
    for (const std::string& p : paths) {
      std::error_code ec;
      if (std::filesystem::exists(p, ec) && !ec)
        return {exit_code::kBadInput, p + " exists; use --force to overwrite it"};
    }
  return {};
}

CLI::Option* add_force_option(CLI::App* cmd, bool& force, const std::string& description) {
  return cmd->add_flag("--force", force, description);
}

}  // namespace invfree
