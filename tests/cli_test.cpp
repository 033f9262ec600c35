// The `invfree` executable end to end: outputs of `simulate`, and one-line errors with
// exit code 2 for bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

struct CommandResult {
  int code;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

CommandResult run(const std::string& args) {
  const std::string dir = ::testing::TempDir();
  // ctest runs tests in parallel processes: name the capture files after this one.
  static int counter = 0;
  const std::string tag = std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const std::string out = dir + "/cli_out_" + tag + ".txt", err = dir + "/cli_err_" + tag + ".txt";
  const std::string cmd = std::string(INVFREE_EXE) + " " + args + " >" + out + " 2>" + err;
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

TEST(Cli, SimulateWritesCsvAndObj) {
  const std::string dir = ::testing::TempDir() + "/cli_sim_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  const CommandResult r = run("simulate --scene compress --steps 5 --csv " + dir + "/c.csv --obj " + dir + "/obj");
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream csv(slurp(dir + "/c.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "step,t,newton_iters,residual,energy,min_det_F,max_det_F,min_gap,ceiling_y,wall_ms");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 5);
  for (int k = 0; k <= 5; ++k) ASSERT_TRUE(std::filesystem::exists(dir + "/obj/" + std::to_string(k) + ".obj"));
  std::istringstream obj(slurp(dir + "/obj/0.obj"));
  int v = 0, f = 0;
  while (std::getline(obj, line)) {
    if (line.rfind("v ", 0) == 0) {
      ++v;
      EXPECT_EQ(line.substr(line.size() - 4), " 0.0");
    }
    if (line.rfind("f ", 0) == 0) ++f;
  }
  EXPECT_EQ(v, 25);
  EXPECT_EQ(f, 32);
  EXPECT_NE(slurp(dir + "/obj/0.obj").find("f 1 6 7\n"), std::string::npos);  // 1-based
}

TEST(Cli, BadInputExitsTwoWithOneLine) {
  const std::string dir = ::testing::TempDir();
  { std::ofstream(dir + "/bad_nu.toml") << "[material]\nE = 1e5\nnu = 0.7\n"; }
  const std::string cases[] = {
      "simulate --scene nosuchscene",
      "simulate --scene " + dir + "/bad_nu.toml",
      "simulate --set material.nu=0.5",
      "simulate --set material.E=-1",
      "simulate --set time.h=0",
      "simulate --set mesh.n_seg=0",
      "simulate --set bogus.key=1",
      "simulate --steps -4",
      "simulate --steps many",
      "simulate --no-such-flag",
      "frobnicate",
  };
  for (const auto& args : cases) {
    const CommandResult r = run(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("invfree: ", 0), 0u) << r.err;
  }
  EXPECT_NE(run("simulate --scene " + dir + "/bad_nu.toml").err.find("bad_nu.toml:3: material.nu"),
            std::string::npos);
}

TEST(Cli, HelpShowsDefaultsAndExitCodes) {
  const CommandResult top = run("--help");
  EXPECT_EQ(top.code, 0);
  EXPECT_NE(top.out.find("Exit codes"), std::string::npos);
  const CommandResult sim = run("simulate --help");
  EXPECT_EQ(sim.code, 0);
  EXPECT_NE(sim.out.find("compress"), std::string::npos);
  EXPECT_NE(sim.out.find("300"), std::string::npos);
}

TEST(Cli, NewtonFailureExitsThree) {
  const CommandResult r = run("simulate --steps 3 --set time.max_newton=1 --set time.tol=1e-14");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("step 1 failed: newton-failed"), std::string::npos) << r.err;
}

}  // namespace
