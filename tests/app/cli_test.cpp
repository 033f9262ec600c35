// The `invfree` executable end to end: outputs of `simulate`, and one-line errors with
// exit code 2 for bad input.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "tests/run_command.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

using test::CommandResult;
using test::slurp;

CommandResult run(const std::string& args) {
  return test::run_command(::invfree::test::exe_path(), args, false);
}

TEST(Cli, SimulateWritesCsvAndObj) {
  const std::string dir = ::testing::TempDir() + "/cli_sim_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  const CommandResult r =
      run("simulate --scene compress --steps 5 --csv " + dir + "/c.csv --obj " + dir + "/obj");
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream csv(slurp(dir + "/c.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(
      line,
      "step,t,newton_iters,residual,incremental_potential,min_det_F,max_det_F,min_gap,"
      "ceiling_y,kinetic,elastic,gravitational,contact,min_self_gap,self_intersecting,wall_ms");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 5);
  for (int k = 0; k <= 5; ++k)
    ASSERT_TRUE(std::filesystem::exists(dir + "/obj/" + std::to_string(k) + ".obj"));
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

// The CSV's self_intersecting column (the one before wall_ms, the last) of every row.
std::vector<int> self_intersecting_column(const std::string& path) {
  std::istringstream csv(slurp(path));
  std::string line;
  std::getline(csv, line);
  std::vector<int> flags;
  while (std::getline(csv, line)) {
    const std::string head = line.substr(0, line.rfind(','));
    flags.push_back(std::stoi(head.substr(head.rfind(',') + 1)));
  }
  return flags;
}

// Switched off, self-contact lets the fold at n_seg 64 pass through itself (between steps
// 200 and 300): simulate says so once on stderr, naming the step and the edges, and the
// CSV flags that step and the crossing ones after it. A run without a crossing says nothing.
TEST(Cli, SimulateWarnsOnceWhenTheBoundaryCrossesItselfWithoutSelfContact) {
  const std::string dir = ::testing::TempDir() + "/cli_cross_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  const CommandResult r =
      run("simulate --scene compress --set mesh.n_seg=64 --set "
          "self_contact.enabled=false --steps 300 --csv " +
          dir + "/off.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  size_t count = 0;
  for (size_t at = r.err.find("warning"); at != std::string::npos;
       at = r.err.find("warning", at + 1))
    ++count;
  EXPECT_EQ(count, 1u) << r.err;
  const size_t step_at = r.err.find("invfree: warning: step ");
  ASSERT_NE(step_at, std::string::npos) << r.err;
  const int warned_step = std::stoi(r.err.substr(step_at + 23));
  EXPECT_NE(r.err.find(": boundary edges "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("without self-contact"), std::string::npos) << r.err;
  const std::vector<int> flags = self_intersecting_column(dir + "/off.csv");
  ASSERT_EQ(flags.size(), 300u);
  const auto first = std::find(flags.begin(), flags.end(), 1);
  ASSERT_NE(first, flags.end()) << "no row flagged";
  EXPECT_EQ(first - flags.begin() + 1, warned_step);
  EXPECT_GT(warned_step, 150);
  // A run that does not cross itself (the coarse default): no warning, no flag.
  const CommandResult quiet =
      run("simulate --scene compress --set self_contact.enabled=false "
          "--steps 300 --csv " +
          dir + "/coarse.csv");
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  for (int flag : self_intersecting_column(dir + "/coarse.csv")) EXPECT_EQ(flag, 0);
  std::filesystem::remove_all(dir);
}

TEST(Cli, AShapeAndItsKeysInAnyOrder) {
  // mesh.shape is applied after the keys it reads, so either order of --set works.
  const std::string outline =
      " --set 'mesh.outline=[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]'";
  for (const std::string& args : {"simulate --steps 2 --set mesh.shape=polygon" + outline,
                                  "simulate --steps 2" + outline + " --set mesh.shape=polygon"}) {
    const CommandResult r = run(args);
    EXPECT_EQ(r.code, 0) << args << "\n" << r.err;
    EXPECT_NE(r.out.find("compress: 2 steps"), std::string::npos) << r.out;
  }
  // A bad shape: one line naming the key, exit 2.
  const CommandResult bad =
      run("simulate --steps 2 --set mesh.shape=polygon --set 'mesh.outline=[[0, 0], [1, 1], [1, "
          "0], [0, 1]]'");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("mesh.outline: "), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

// A static scene with a dead load: it runs; an unsupported body, a traction box that holds
// no edge and a NaN force are each one line naming the key, exit 2, before any step.
TEST(Cli, StaticScenesAndTheirBadLoads) {
  const std::string dir = ::testing::TempDir();
  const std::string base =
      "[mesh]\nshape = \"rectangle\"\nwidth = 2.0\nheight = 0.5\n"
      "[solver]\nintegrator = \"static\"\n[time]\nh = 1.0\ntol = 1e-9\n";
  const std::string held = "[fixed]\nbox_min = [-1.0, -0.25]\nbox_max = [-1.0, 0.25]\n";
  auto traction = [](const std::string& box_min, const std::string& force,
                     const std::string& box_max = "[1.0, 0.25]") {
    return "[[traction]]\nbox_min = " + box_min + "\nbox_max = " + box_max + "\nforce = " + force +
           "\n";
  };
  {
    std::ofstream(dir + "/static_ok.toml") << base + held + traction("[1.0, -0.25]", "[0.0, -1.0]");
  }
  { std::ofstream(dir + "/static_free.toml") << base + traction("[1.0, -0.25]", "[0.0, -1.0]"); }
  {
    std::ofstream(dir + "/static_nobox.toml")
        << base + held + traction("[0.2, -0.1]", "[0.0, -1.0]", "[0.3, 0.1]");
  }
  {
    std::ofstream(dir + "/static_nan.toml")
        << base + held + traction("[1.0, -0.25]", "[nan, -1.0]");
  }
  const CommandResult ok = run("simulate --steps 2 --scene " + dir + "/static_ok.toml");
  EXPECT_EQ(ok.code, 0) << ok.err;
  const std::pair<const char*, const char*> bad[] = {
      {"static_free", "solver.integrator: static equilibrium needs every body held"},
      {"static_nobox", "traction.box_min: the box [0.2, 0.3] x [-0.1, 0.1] holds no boundary edge"},
      {"static_nan", "traction.force: element 0: must be a finite number"}};
  for (const auto& [name, expected] : bad) {
    const CommandResult r =
        run(std::string("simulate --steps 2 --scene ") + dir + "/" + name + ".toml");
    EXPECT_EQ(r.code, 2) << name;
    EXPECT_NE(r.err.find(expected), std::string::npos) << name << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

// [reduced]: a modal cut inside a degenerate pair (the square's modes 5 and 6), a cut inside
// the three rigid modes, a polynomial order above 3 and a basis with a ceiling are one line
// each, exit 2; a valid basis runs.
TEST(Cli, ReducedBasesAndTheirBadCounts) {
  const CommandResult ok = run("simulate --steps 3 --scene course-9-modal --set reduced.modes=6");
  EXPECT_EQ(ok.code, 0) << ok.err;
  const std::pair<const char*, const char*> bad[] = {
      {"--scene course-9-modal --set reduced.modes=5",
       "reduced.modes: 5 splits a degenerate group of eigenvalues (modes 5 and 6: "},
      {"--scene course-9-modal --set reduced.modes=2", "use more than 2"},
      {"--scene course-9-cubic --set reduced.order=4", "reduced.order: must be between 1 and 3"},
      {"--scene course-9-modal --set reduced.modes=500", "reduced.modes: 500 modes of a mesh with 242 unknowns"},
      {"--scene course-9-affine --set ceiling.enabled=true", "a reduced basis has no ceiling"}};
  for (const auto& [args, expected] : bad) {
    const CommandResult r = run(std::string("simulate --steps 2 ") + args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
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
  std::printf("bad inputs tried (command line, basic): %zu, all clean one-line errors\n",
              std::size(cases));
  EXPECT_NE(run("simulate --scene " + dir + "/bad_nu.toml").err.find("bad_nu.toml:3: material.nu"),
            std::string::npos);
}

// A dotted key or table header tens of thousands of levels deep (100 kB, under the 1 MiB
// limit) overflowed toml++'s recursion (SIGSEGV, exit 139). Every command that reads a
// scene refuses it with one line and exit 2, before toml++ sees it.
TEST(Cli, DeepDottedKeysExitTwoWithOneLine) {
  const std::string dir = ::testing::TempDir() + "/cli_deep_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  std::string chain;
  for (int k = 0; k < 50000; ++k) chain += "a.";
  const std::pair<const char*, std::string> files[] = {
      {"key", chain + "b = 1\n"},
      {"header", "[" + chain + "b]\n"},
      {"array_header", "[[" + chain + "b]]\n"},
  };
  for (const auto& [name, text] : files) {
    const std::string path = dir + "/" + name + ".toml";
    { std::ofstream(path) << text; }
    const std::string commands[] = {"simulate --steps 1 --scene ",
                                    "render --frames 1 --out " + dir + "/out --scene "};
    for (const std::string& command : commands) {
      const CommandResult r = run(command + path);
      EXPECT_EQ(r.code, 2) << command << name << "\n" << r.err.substr(0, 300);
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err.substr(0, 300);
      EXPECT_EQ(r.err, "invfree: " + path +
                           ":1: malformed TOML: a dotted key with more than two parts (a scene "
                           "needs section.key)\n");
    }
  }
  std::filesystem::remove_all(dir);
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

// Every kind of bad command-line value and scene path: exit code 2, one line on stderr
// naming what is wrong, nothing on stdout (no step ran), no crash or hang.
TEST(Cli, EveryBadCommandLineValueExitsTwo) {
  const std::string dir = ::testing::TempDir() + "/cli_bad_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir + "/subdir");
  {
    std::ofstream(dir + "/binary.toml", std::ios::binary)
        << std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
  }
  { std::ofstream(dir + "/malformed.toml") << "[mesh\nn_seg = 4\n"; }
  { std::ofstream(dir + "/typo.toml") << "[mesh]\nnseg = 4\n"; }
  { std::ofstream(dir + "/both.toml") << "[material]\nE = 1e5\nnu = 0.3\nmu = 5\n"; }
  { std::ofstream(dir + "/through.toml") << "[ground]\ny = 0\n"; }
  { std::ofstream(dir + "/ceiling.toml") << "[ground]\ny = -1\n[ceiling]\ny = -1.5\nstop = -2\n"; }
  ASSERT_EQ(::mkfifo((dir + "/fifo.toml").c_str(), 0644), 0);
  struct Case {
    std::string args, expected;
  };
  const std::vector<Case> cases = {
      {"simulate --steps -1", "--steps"},
      {"simulate --steps 100000001", "--steps"},
      {"simulate --steps 1e9", "--steps"},
      {"simulate --steps 2.5", "--steps"},
      {"simulate --steps ''", "--steps"},
      {"simulate --steps 99999999999999999999", "--steps"},
      {"simulate --steps", "--steps"},
      {"simulate --scene", "--scene"},
      {"simulate --scene ''",
       ": no such file, and not a built-in scene (bunny, c-shape, compress, course-0-free-fall, "
       "course-0-mass-spring, course-0-spring, course-1-mass-spring, "
       "course-2-dirichlet, course-3-contact, course-4-friction, course-5-moving-dirichlet, "
      "course-9-affine, course-9-cubic, course-9-modal, course-9-quadratic, drop, "
       "modes-cantilever, plate-hole, ring, "
       "stack, stack-friction)"},
      {"simulate --scene comprss", "comprss: no such file, and not a built-in scene"},
      {"simulate --scene " + dir + "/subdir", dir + "/subdir: is a directory, not a scene file"},
      {"simulate --scene " + dir + "/binary.toml", dir + "/binary.toml: not a text file"},
      {"simulate --scene " + dir + "/fifo.toml", dir + "/fifo.toml: not a regular file"},
      {"simulate --scene /dev/zero", "/dev/zero: not a regular file"},
      {"simulate --scene /proc/self/mem", "/proc/self/mem: could not read the file"},
      {"simulate --scene " + dir + "/malformed.toml", dir + "/malformed.toml:1: malformed TOML"},
      {"simulate --scene " + dir + "/typo.toml",
       dir + "/typo.toml:2: mesh.nseg: unknown key (did you mean \"n_seg\"?)"},
      {"simulate --scene " + dir + "/both.toml",
       dir + "/both.toml:2: material.E: give either E and nu or mu and lambda"},
      {"simulate --scene " + dir + "/through.toml",
       dir + "/through.toml:2: ground.y: the square starts on or through"},
      {"simulate --scene " + dir + "/ceiling.toml",
       dir + "/ceiling.toml:4: ceiling.y: must be above ground.y"},
      {"simulate --set", "--set"},
      {"simulate --set material.nu", "--set material.nu: expected section.key=value"},
      {"simulate --set 'material.nu=0.3\nmesh.side=2'",
       "--set material.nu=0.3\\nmesh.side=2: material.nu: expected a single value"},
      {"simulate --set 'mesh.n$(echo x)=1'", "unknown key"},
      {"simulate --set time.h=-0.01", "--set time.h=-0.01: time.h: must be a finite number > 0"},
      {"simulate --set time.h=nan", "time.h: must be a finite number"},
      {"simulate --set mesh.n_seg=100000", "mesh.n_seg: must be between 1 and 4096"},
      {"simulate --set ground.friction=-1", "ground.friction: must be a finite number >= 0"},
      {"simulate --set barrier.kappa=0", "barrier.kappa: must be a finite number > 0"},
      {"simulate --set ceiling.y=-1.2", "ceiling.y: must be above ground.y"},
      {"simulate --set material.model=neohookean", "unknown value \"neohookean\" (expected one of"},
      {"simulate --set gravity.g=1", "gravity.g: expected an array of two numbers"},
      {"simulate --obj " + dir,
       dir + ": directory is not empty (use --force to write into it anyway)"},
      // An empty path is bad input for every output option (not "" + "/study.csv", a file
      // at the filesystem root).
      {"simulate --obj ''", "--obj: empty path"},
      {"simulate --csv ''", "--csv: empty path"},
      {"render --out ''", "--out: empty path"},
      {"bench --out '' --sizes 4", "--out: empty path"},
      {"study --out ''", "--out: empty path"},
      {"stability --out ''", "--out: empty path"},
      {"live --record ''", "--record: empty path"},
      {"live --screenshot ''", "--screenshot: empty path"},
      {"live --screenshot-dir ''", "--screenshot-dir: empty path"},
      {"simulate extra_positional", "extra_positional"},
      {"", "subcommand"},
      {"simulate --steps 5 --steps 6", "--steps"},
      {"simulate --forc", "--forc"},
  };
  for (const auto& c : cases) {
    const CommandResult r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("invfree: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos)
        << c.args << "\nexpected: " << c.expected << "\ngot: " << r.err;
    EXPECT_EQ(r.out, "") << c.args << ": nothing may run on bad input";
  }
  std::printf("bad inputs tried (command line): %zu, all clean one-line errors\n", cases.size());
  std::filesystem::remove_all(dir);
}

TEST(Cli, StepFailureNamesTheStepAndKeepsCompleteOutput) {
  const std::string dir = ::testing::TempDir() + "/cli_fail_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  // Newton's cap of 1 iteration with an unreachable tolerance: the first step fails.
  const CommandResult r =
      run("simulate --steps 3 --set time.max_newton=1 --set time.tol=1e-14 --csv " + dir +
          "/run.csv --obj " + dir + "/obj");
  EXPECT_EQ(r.code, 3);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("invfree: step 1 failed: newton-failed: Newton reached its iteration cap "
                       "(1) (t = 0.01 s)"),
            std::string::npos)
      << r.err;
  // The outputs describe the steps that succeeded: the initial mesh and an empty table.
  EXPECT_TRUE(std::filesystem::exists(dir + "/obj/0.obj"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/obj/1.obj"));
  EXPECT_EQ(
      slurp(dir + "/run.csv"),
      "step,t,newton_iters,residual,incremental_potential,min_det_F,max_det_F,min_gap,"
      "ceiling_y,kinetic,elastic,gravitational,contact,min_self_gap,self_intersecting,wall_ms\n");
  std::filesystem::remove_all(dir);
}

// Issue 32 item 11: a scene file without [gravity] runs without gravity, and the command
// says so once on stderr (a student's stack floated until the ceiling came); a built-in
// scene, which leaves sections out on purpose, gets no note; a file with every error.
TEST(Cli, SceneFileWithoutGravitySaysSoOnce) {
  const std::string path =
      ::testing::TempDir() + "/no_gravity_" + std::to_string(::getpid()) + ".toml";
  {
    std::ofstream f(path);
    f << "[mesh]\nn_seg = 2\n[ground]\ny = -1.0\n[ceiling]\ny = 0.6\n";
  }
  const CommandResult r = run("simulate --steps 2 --scene " + path);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string note = "invfree: note: " + path + ": no [gravity] section, so gravity is off";
  EXPECT_EQ(r.err.rfind(note, 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const CommandResult builtin = run("simulate --steps 2 --scene course-0-free-fall");
  ASSERT_EQ(builtin.code, 0) << builtin.err;
  EXPECT_EQ(builtin.err, "");
  {
    std::ofstream f(path);
    f << "[mesh]\nn_segs = 2\nsid = 1\n";
  }
  const CommandResult bad = run("simulate --steps 2 --scene " + path);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find(path + ":2: mesh.n_segs"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find(path + ":3: mesh.sid"), std::string::npos) << bad.err;
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace invfree
