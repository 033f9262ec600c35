// Runs the invfree executable the way a user does, for the command-line tests: stdout
// and stderr captured into files named after this process and call (ctest runs tests in
// parallel processes), the exit code decoded (-1 when the process did not exit
// normally). `headless` removes DISPLAY and WAYLAND_DISPLAY and gives stdin /dev/null;
// `env` ("NAME=value ...") is set for the command only. And the CSV files they check.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace invfree::test {

struct CommandResult {
  int code;
  std::string out, err;
};

// True when `s` is one line: not empty, and its only newline ends it (what every error
// message of the program must be).
inline bool one_line(const std::string& s) {
  return !s.empty() && s.find('\n') == s.size() - 1;
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline CommandResult run_command(const std::string& exe, const std::string& args, bool headless,
                                 const std::string& env = "") {
  static int counter = 0;
  const std::string tag = std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const std::string out = ::testing::TempDir() + "/invfree_out_" + tag;
  const std::string err = ::testing::TempDir() + "/invfree_err_" + tag;
  std::string cmd = headless      ? "env -u DISPLAY -u WAYLAND_DISPLAY " + env + " "
                    : env.empty() ? ""
                                  : "env " + env + " ";
  cmd += exe + " " + args + " >" + out + " 2>" + err + (headless ? " </dev/null" : "");
  const int status = std::system(cmd.c_str());
  CommandResult r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
  std::remove(out.c_str());
  std::remove(err.c_str());
  return r;
}

// A CSV file's rows, split at commas (no quoting: the program's CSVs have none); a line
// ending in a comma has an empty last cell.
inline std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace invfree::test
