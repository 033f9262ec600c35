// Every quantity a step reports is a number (issue 31 item 6): a step whose accepted state
// has an infinite energy or a det F that is not finite fails (NonFinite; `simulate` exits
// 3), also where positions and velocities are finite; and `simulate`'s summary gives the
// range of det F over the whole run, in digits a person reads (item 11).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "energy_report.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "simulation.h"
#include "tests/run_command.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

SceneDef scene_with(const std::string& name, const std::vector<std::string>& overrides) {
  const SceneLoad load = load_builtin_scene(name);
  EXPECT_TRUE(load.scene) << load.error;
  SceneDef s = load.scene ? *load.scene : SceneDef{};
  EXPECT_EQ(apply_overrides(s, overrides), "");
  return s;
}

// Steps `scene` until a step fails or `steps` are done; every accepted state's reported
// quantities are finite. Returns the failing report (status Ok when none failed).
StepReport run_checking_every_state(const SceneDef& scene, int steps) {
  Simulation sim = make_simulation(scene);
  for (int k = 0; k < steps; ++k) {
    const StepReport r = step(sim);
    if (r.status != StepStatus::Ok) return r;
    const EnergyReport e = energy_report(sim);
    for (double v : {e.kinetic, e.elastic, e.gravitational, e.contact, r.energy, r.residual})
      EXPECT_TRUE(std::isfinite(v)) << "step " << sim.step_count << " accepted " << v;
    for (double d : triangle_det_f(sim))
      EXPECT_TRUE(std::isfinite(d)) << "step " << sim.step_count << " det F " << d;
  }
  return {};
}

TEST(FiniteReport, AnInfiniteKineticEnergyFailsTheStep) {
  // Symplectic Euler, the springs' chapter 0: 1e200 m/s keeps positions finite, not m v^2.
  const SceneDef s = scene_with("course-0-mass-spring", {"initial.velocity=[0, 1e200]"});
  const StepReport r = run_checking_every_state(s, 3);
  EXPECT_EQ(r.status, StepStatus::NonFinite);
  EXPECT_NE(r.message.find("kinetic energy is not finite"), std::string::npos) << r.message;
}

TEST(FiniteReport, AnInfiniteSpringEnergyFailsTheStep) {
  // Springs of 1e300 N/m stretched by the chapter's start: their energy overflows.
  const SceneDef s = scene_with("course-1-mass-spring",
                                {"solver.integrator=symplectic-euler", "mass_spring.stiffness=1e300"});
  const StepReport r = run_checking_every_state(s, 3);
  EXPECT_EQ(r.status, StepStatus::NonFinite);
  EXPECT_NE(r.message.find("is not finite"), std::string::npos) << r.message;
}

TEST(FiniteReport, SymplecticEulersEnergyIsTheAcceptedStates) {
  const SceneDef s = scene_with("course-0-free-fall", {});
  Simulation sim = make_simulation(s);
  for (int k = 0; k < 3; ++k) {
    const StepReport r = step(sim);
    ASSERT_EQ(r.status, StepStatus::Ok) << r.message;
    const EnergyReport e = energy_report(sim);
    EXPECT_DOUBLE_EQ(r.energy, e.kinetic + e.elastic + e.gravitational);
  }
}

using test::CommandResult;

CommandResult run(const std::string& args) {
  return test::run_command(::invfree::test::exe_path(), args, false);
}

TEST(FiniteReport, SimulateExitsThreeAndPrintsNoNan) {
  const CommandResult r =
      run("simulate --scene course-0-mass-spring --set initial.velocity=[0,1e200] --steps 20");
  EXPECT_EQ(r.code, 3) << r.out << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("inf"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("non-finite: the kinetic energy is not finite"), std::string::npos)
      << r.err;
  EXPECT_TRUE(test::one_line(r.err)) << r.err;
}

TEST(FiniteReport, AHugeDetFIsPrintedInDigitsAPersonReads) {
  // g = 1e150 m/s^2 stretches the springs' square to det F ~ 1e148: finite, and printed as
  // such (four significant digits), not as 150 digits.
  const CommandResult r =
      run("simulate --scene course-0-mass-spring --set gravity.g=[0,-1e150] --steps 5");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("e+"), std::string::npos) << r.out;
  EXPECT_LT(r.out.size(), 200u) << r.out;
}

TEST(FiniteReport, TheSummarysDetFIsTheWholeRunsRange) {
  // `drop` hits the ground and springs back: its lowest det F is at the impact, not at the
  // end of the run.
  const std::string dir = ::testing::TempDir() + "/finite_report_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  const CommandResult r = run("simulate --scene drop --steps 60 --csv " + dir + "/run.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = test::read_csv(dir + "/run.csv");
  ASSERT_EQ(rows.size(), 61u);
  double lo = 1.0, hi = 1.0, last_lo = 0.0;  // step 0, the rest mesh: det F = 1
  for (size_t k = 1; k < rows.size(); ++k) {
    lo = std::min(lo, std::stod(rows[k][5]));
    hi = std::max(hi, std::stod(rows[k][6]));
    last_lo = std::stod(rows[k][5]);
  }
  ASSERT_LT(lo, last_lo - 1e-3) << "the scene must reach its lowest det F before its end";
  char expected[96];
  std::snprintf(expected, sizeof expected, "det F in [%.4f, %.4f] over steps 0..60", lo, hi);
  EXPECT_NE(r.out.find(expected), std::string::npos) << r.out << "expected: " << expected;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace invfree
