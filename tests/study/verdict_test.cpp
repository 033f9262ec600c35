// Run classification: the names, the step-status mapping, the energy criterion, the
// bounding box, inversion (including an inverted start that recovers) and whole runs.
#include "app/study/verdict.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/study/methods.h"
#include "app/study/run.h"
#include "app/study/stress_scenes.h"
#include "scene_io/scene_file.h"

namespace invfree {
namespace {

TEST(Verdict, NamesAreTheTableSpellings) {
  EXPECT_STREQ(verdict_name(Verdict::Ok), "ok");
  EXPECT_STREQ(verdict_name(Verdict::Inverted), "inverted");
  EXPECT_STREQ(verdict_name(Verdict::Penetrated), "penetrated");
  EXPECT_STREQ(verdict_name(Verdict::NonFinite), "non-finite");
  EXPECT_STREQ(verdict_name(Verdict::NewtonFailed), "newton-failed");
  EXPECT_STREQ(verdict_name(Verdict::BlewUp), "blew-up");
  EXPECT_STREQ(verdict_name(Verdict::NotApplicable), "n/a");
}

TEST(Verdict, StepStatusesMapToVerdicts) {
  EXPECT_EQ(verdict_from_status(StepStatus::Ok), Verdict::Ok);
  EXPECT_EQ(verdict_from_status(StepStatus::NewtonFailed), Verdict::NewtonFailed);
  EXPECT_EQ(verdict_from_status(StepStatus::LinearSolveFailed), Verdict::NewtonFailed);
  EXPECT_EQ(verdict_from_status(StepStatus::NonFinite), Verdict::NonFinite);
  EXPECT_EQ(verdict_from_status(StepStatus::Inverted), Verdict::Inverted);
  EXPECT_EQ(verdict_from_status(StepStatus::Penetrated), Verdict::Penetrated);
}

TEST(Verdict, EnergyBudgetCountsTheStartAndTheCeilingWork) {
  // floor 0, start 100 J, ceiling did 50 J: budget 150 J, factor 10 -> 1500 J allowed.
  EXPECT_FALSE(energy_exceeds_budget(1500.0, 0.0, 100.0, 50.0, 10.0, 1e-9));
  EXPECT_TRUE(energy_exceeds_budget(1500.1, 0.0, 100.0, 50.0, 10.0, 1e-9));
  // Offset invariant: shifting every energy by a constant changes nothing.
  EXPECT_FALSE(energy_exceeds_budget(1500.0 - 7e4, -7e4, 100.0 - 7e4, 50.0, 10.0, 1e-9));
  EXPECT_TRUE(energy_exceeds_budget(1500.1 - 7e4, -7e4, 100.0 - 7e4, 50.0, 10.0, 1e-9));
  // Nothing supplied: the minimum budget stops rounding noise from counting.
  EXPECT_FALSE(energy_exceeds_budget(1e-12, 0.0, 0.0, 0.0, 10.0, 1e-9));
  EXPECT_TRUE(energy_exceeds_budget(1e-6, 0.0, 0.0, 0.0, 10.0, 1e-9));
  EXPECT_TRUE(energy_exceeds_budget(std::nan(""), 0.0, 1.0, 0.0, 10.0, 1e-9));
}

SceneDef quiet_scene() {
  SceneDef s;  // compress, at rest in the air
  s.has_ceiling = false;
  return s;
}

TEST(RunMonitor, FlagsEnergyNoSceneCanSupply) {
  Simulation sim = make_simulation(quiet_scene());
  RunMonitor m;
  m.start(sim, 1.0);
  std::string why;
  EXPECT_EQ(m.after_step(sim, &why), Verdict::Ok);
  // 1000 kg at 30 m/s is 450 kJ, far over 10 x the 9.8 kJ the drop can give.
  for (int i = 0; i < sim.mesh.node_count(); ++i) sim.v[2 * i] = 30.0;
  EXPECT_EQ(m.after_step(sim, &why), Verdict::BlewUp);
  EXPECT_NE(why.find("energy"), std::string::npos) << why;
}

TEST(RunMonitor, FlagsNodesFarOutsideTheScene) {
  Simulation sim = make_simulation(quiet_scene());
  RunMonitor m;
  m.start(sim, 1.0);
  std::string why;
  sim.x[0] +=
      50.0;  // one node 50 m away: elastic energy alone would trip too, so check the message
  EXPECT_EQ(m.after_step(sim, &why), Verdict::BlewUp);
  EXPECT_NE(why.find("bounding box"), std::string::npos) << why;
}

TEST(RunMonitor, InversionOfAValidMeshIsAFailureForEveryModel) {
  SceneDef s = quiet_scene();
  s.model = Model::Linear;  // the core allows det F <= 0 here; the stability table does not
  Simulation sim = make_simulation(s);
  RunMonitor m;
  m.start(sim, 1.0);
  std::string why;
  const auto& tri = sim.mesh.triangles[0];
  // Move the first vertex through the opposite edge.
  const Vec2 mid = 0.5 * (sim.x.segment<2>(2 * tri[1]) + sim.x.segment<2>(2 * tri[2]));
  sim.x.segment<2>(2 * tri[0]) = 2.0 * mid - sim.x.segment<2>(2 * tri[0]);
  EXPECT_EQ(m.after_step(sim, &why), Verdict::Inverted) << why;
}

TEST(RunMonitor, TheStudyMayLetInvertibleModelsInvert) {
  SceneDef s = quiet_scene();
  s.model = Model::Linear;
  Simulation sim = make_simulation(s);
  RunMonitor m;
  m.inversion_is_failure = false;
  m.start(sim, 1.0);
  const auto& tri = sim.mesh.triangles[0];
  const Vec2 mid = 0.5 * (sim.x.segment<2>(2 * tri[1]) + sim.x.segment<2>(2 * tri[2]));
  sim.x.segment<2>(2 * tri[0]) = 2.0 * mid - sim.x.segment<2>(2 * tri[0]);
  std::string why;
  EXPECT_EQ(m.after_step(sim, &why), Verdict::Ok) << why;
  EXPECT_EQ(m.at_end(&why), Verdict::Ok);
}

TEST(RunMonitor, AnInvertedStartMayRecoverButNotInvertAgain) {
  SceneDef s = quiet_scene();
  s.model = Model::StableNeoHookean;
  s.n_seg = 8;
  s.jitter = 0.45;
  s.seed = 3;  // four inverted triangles (see assets/scenes/stress-jitter-inverted.toml)
  Simulation sim = make_simulation(s);
  RunMonitor m;
  m.start(sim, 1.0);
  ASSERT_TRUE(m.started_inverted);
  std::string why;
  EXPECT_EQ(m.after_step(sim, &why), Verdict::Ok) << "still inverted, not yet a failure";
  EXPECT_EQ(m.at_end(&why), Verdict::Inverted) << "but never recovering is";
  const VecX start = sim.x;
  // The unjittered square: every det F = 1, recovered.
  for (int i = 0; i < sim.mesh.node_count(); ++i) sim.x.segment<2>(2 * i) = sim.mesh.rest[i];
  EXPECT_EQ(m.after_step(sim, &why), Verdict::Ok);
  EXPECT_EQ(m.at_end(&why), Verdict::Ok);
  sim.x = start;
  EXPECT_EQ(m.after_step(sim, &why), Verdict::Inverted) << "inverting again after recovering fails";
}

TEST(RunScene, LecturesMethodRunsTheDemoAndSamplesItsTimes) {
  SceneDef s;
  RunOptions o;
  o.duration = 0.5;
  o.sample_times = {0.1, 0.5};
  const RunResult r = run_scene(s, o);
  EXPECT_EQ(r.verdict, Verdict::Ok) << r.message;
  EXPECT_EQ(r.steps, 50);
  ASSERT_EQ(r.samples.size(), 2u);
  double top = -1e9;
  for (int i = 1; i < r.samples[0].size(); i += 2) top = std::max(top, r.samples[0][i]);
  EXPECT_NEAR(top, 0.5 - 0.5 * 9.81 * 0.1 * 0.1, 0.01)
      << "free fall for 0.1 s (implicit Euler: O(h) off)";
  EXPECT_GT(r.wall_s, 0.0);
  EXPECT_GE(r.newton_iterations, 50);
}

TEST(RunScene, SampleTimesMustBeMultiplesOfTheStep) {
  std::vector<long> steps;
  EXPECT_EQ(sample_steps({0.4, 0.8}, 0.04, &steps), "");
  EXPECT_EQ(steps, (std::vector<long>{10, 20}));
  EXPECT_NE(sample_steps({0.41}, 0.04, &steps), "");
  SceneDef s;
  RunOptions o;
  o.sample_times = {0.015};
  EXPECT_EQ(run_scene(s, o).verdict, Verdict::NotApplicable);
}

TEST(RunScene, ExplicitEulerAtTheImplicitStepFails) {
  SceneDef s;
  ASSERT_EQ(apply_method(*find_method("symplectic-euler"), s, false), "");
  RunOptions o;
  o.duration = 1.0;
  const RunResult r = run_scene(s, o);  // h = 0.01 is far above its stability limit
  EXPECT_NE(r.verdict, Verdict::Ok);
  EXPECT_NE(r.verdict, Verdict::NotApplicable);
  EXPECT_GT(r.fail_step, 0);
  EXPECT_LE(r.fail_step, 100);
}

TEST(RunScene, NeoHookeanCannotStartInverted) {
  for (const StressScene& st : stress_scenes()) {
    if (st.name != "stress-jitter-inverted") continue;
    std::string error;
    auto scene = load_stress_scene(st, &error);
    ASSERT_TRUE(scene) << error;
    SceneDef s = *scene;
    // Either the override itself refuses the model (the scene parser validates) or the
    // run does: both make the stability cell n/a, naming the inverted start.
    const std::string e = apply_method(*find_method("lecture"), s, true);
    if (!e.empty()) {
      EXPECT_NE(e.find("inverted"), std::string::npos) << e;
      return;
    }
    const RunResult r = run_scene(s, RunOptions{});
    EXPECT_EQ(r.verdict, Verdict::NotApplicable);
    EXPECT_EQ(r.fail_step, 0);
    EXPECT_NE(r.message.find("inverted"), std::string::npos) << r.message;
    return;
  }
  FAIL() << "stress-jitter-inverted is not embedded";
}

}  // namespace
}  // namespace invfree
