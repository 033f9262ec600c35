// The command line's rules (docs/cli.md), end to end through the `invfree` executable:
// E/nu and mu/lambda cannot be mixed with --set (either order), no existing output is
// replaced without --force (every command), typos get the nearest valid word, --version,
// and the help texts make no claims about run times (they would go stale).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "tests/run_command.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

using test::CommandResult;
using test::one_line;
using test::slurp;

CommandResult run(const std::string& args) {
  return test::run_command(::invfree::test::exe_path(), args, false);
}

TEST(CliRules, MixingYoungAndLameOnTheCommandLineExitsTwoInEitherOrder) {
  for (const char* args : {"--set material.E=1e4 --set material.mu=1000",
                           "--set material.mu=1000 --set material.E=1e4",
                           "--set material.lambda=1000 --set material.nu=0.3"}) {
    const CommandResult r = run(std::string("simulate --steps 1 ") + args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_TRUE(one_line(r.err)) << r.err;
    EXPECT_NE(r.err.find("give either E and nu or mu and lambda, not both"), std::string::npos)
        << r.err;
  }
  // Each family alone is fine.
  EXPECT_EQ(run("simulate --steps 1 --set material.E=1e4 --set material.nu=0.3").code, 0);
  EXPECT_EQ(run("simulate --steps 1 --set material.mu=1000 --set material.lambda=2000").code, 0);
}

TEST(CliRules, NoCommandReplacesAnExistingFileWithoutForce) {
  namespace fs = std::filesystem;
  const std::string dir = ::testing::TempDir() + "/cli_rules_" + std::to_string(::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  // Each command's first output, already there: refused before any work, left as it was.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"simulate --steps 2 --csv " + dir + "/run.csv", dir + "/run.csv"},
      {"study --quick --quiet --out " + dir, dir + "/study.csv"},
      {"stability --quick --quiet --out " + dir, dir + "/stability.md"},
      {"bench --sizes 4 --steps 2 --out " + dir, dir + "/bench.csv"},
  };
  for (const auto& [args, file] : cases) {
    { std::ofstream(file) << "precious\n"; }
    const CommandResult r = run(args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_TRUE(one_line(r.err)) << r.err;
    EXPECT_NE(r.err.find(file + " exists; use --force to overwrite it"), std::string::npos)
        << r.err;
    EXPECT_EQ(slurp(file), "precious\n") << args;
    fs::remove(file);
  }
  // With --force the file is replaced (the cheap commands).
  { std::ofstream(dir + "/run.csv") << "precious\n"; }
  EXPECT_EQ(run("simulate --steps 2 --force --csv " + dir + "/run.csv").code, 0);
  EXPECT_EQ(slurp(dir + "/run.csv").rfind("step,t,", 0), 0u);
  { std::ofstream(dir + "/bench.svg") << "precious\n"; }
  const CommandResult b = run("bench --sizes 4 --steps 2 --format svg --force --out " + dir);
  EXPECT_EQ(b.code, 0) << b.err;
  EXPECT_NE(slurp(dir + "/bench.svg").find("<svg"), std::string::npos);
  // --format takes the three words only (not the enum's numbers).
  const CommandResult n = run("bench --sizes 4 --steps 2 --format 2 --force --out " + dir);
  EXPECT_EQ(n.code, 2) << n.err;
  EXPECT_TRUE(one_line(n.err)) << n.err;
  fs::remove_all(dir);
}

TEST(CliRules, TyposGetTheNearestValidWord) {
  struct Case {
    std::string args, expected;
  };
  const std::vector<Case> cases = {
      {"simulate --stpes 10", "did you mean \"--steps\" for \"--stpes\"?"},
      {"simulat", "did you mean \"simulate\" for \"simulat\"?"},
      {"frobnicate",
       "(commands: simulate, bench, render, study, stability, live, inspect, landscape, verify, "
       "modes)"},
      {"simulate --scene compres", "did you mean \"compress\"?"},
      {"simulate --set material.youngs=1", "(keys of [material]: model, E, nu, mu, lambda)"},
      {"study --fromat svg", "did you mean \"--format\" for \"--fromat\"?"},
  };
  for (const Case& c : cases) {
    const CommandResult r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_TRUE(one_line(r.err)) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << ": " << r.err;
  }
  const CommandResult v = run("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_TRUE(std::regex_search(v.out, std::regex("^invfree [0-9]+\\.[0-9]+\\.[0-9]+\n$")))
      << v.out;
}

TEST(CliRules, HelpMakesNoClaimsAboutRunTimes) {
  const CommandResult r = run("--help-all");
  ASSERT_EQ(r.code, 0);
  // "under a minute", "takes 5 s", "about 2 min": figures that depend on the machine and go
  // stale; the help says what a flag does, docs/ give measured times with their commands.
  const std::regex duration(
      "([0-9]+(\\.[0-9]+)? ?(s|sec|seconds?|min|minutes?|hours?)\\b)|(a minute|an hour)",
      std::regex::icase);
  std::smatch m;
  EXPECT_FALSE(std::regex_search(r.out, m, duration)) << "found \"" << m.str() << "\"";
  EXPECT_NE(r.out.find("--format"), std::string::npos);
  EXPECT_NE(r.out.find("--force"), std::string::npos);
}

}  // namespace
}  // namespace invfree
