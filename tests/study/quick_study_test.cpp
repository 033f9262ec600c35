// A quick study must not contradict the full one (issue 32 item 1): it runs as long as the
// full study, through the ceiling's squeeze that decides the verdicts, so symplectic Euler
// is not `ok` (nor on a Pareto front) in `study --quick` where the full study sees it fail;
// and a scene whose errors do not fall with h (stack) is flagged rather than ranked.
// Inversions the model allows end no stability run (item 5).
#include <gtest/gtest.h>

#include <string>

#include "app/study/methods.h"
#include "app/study/run.h"
#include "app/study/stability.h"
#include "app/study/stress_scenes.h"
#include "app/study/study.h"
#include "app/study/study_chart.h"
#include "scene_io/builtin_scenes.h"

namespace invfree {
namespace {

SceneDef builtin(const char* name) {
  const SceneLoad load = load_builtin_scene(name);
  EXPECT_TRUE(load.scene) << load.error;
  return load.scene ? *load.scene : SceneDef{};
}

TEST(QuickStudy, RunsAsLongAsTheFullStudy) {
  for (const char* name : {"compress", "stack"}) {
    const SceneDef s = builtin(name);
    EXPECT_EQ(study_sample_times(s, true), study_sample_times(s, false)) << name;
    // compress: the ceiling meets the square's top at about 1.2 s; the runs go on to 2 s.
    EXPECT_GE(study_sample_times(s, true).back(), 2.0 - 1e-9) << name;
  }
}

TEST(QuickStudy, SymplecticEulerFailsAtEveryHAsInTheFullStudy) {
  SweepOptions o;
  o.quick = true;
  o.methods = {"symplectic-euler"};
  const StudyResult r = run_study(builtin("compress"), o);
  int rows = 0;
  for (const StudyRow& row : r.rows) {
    ASSERT_EQ(row.method, "symplectic-euler");
    ++rows;
    EXPECT_NE(row.failure, "ok") << "h = " << row.h << ": the squeeze makes it fail";
  }
  EXPECT_EQ(rows, 3);
  for (const Series& s : study_panels(r)[0].series)
    EXPECT_TRUE(s.x.empty()) << s.label << ": nothing of a failed run is plotted";
}

TEST(QuickStudy, ErrorsThatDoNotFallWithHAreFlagged) {
  SweepOptions o;
  o.quick = true;
  o.methods = {"lecture"};
  const StudyResult stack = run_study(builtin("stack"), o);
  const ModelConvergence* c = model_convergence(stack, "neo-hookean");
  ASSERT_NE(c, nullptr);
  EXPECT_TRUE(c->judged);
  EXPECT_FALSE(c->converges) << "slope " << c->slope;
  EXPECT_EQ(non_converging_models(stack).size(), 1u);
  EXPECT_NE(study_panels(stack)[0].title.find("DO NOT CONVERGE"), std::string::npos);
  // compress's errors fall with h: its front is drawn.
  const StudyResult compress = run_study(builtin("compress"), o);
  c = model_convergence(compress, "neo-hookean");
  ASSERT_NE(c, nullptr);
  EXPECT_TRUE(c->converges) << "slope " << c->slope;
  EXPECT_EQ(study_panels(compress)[0].title.find("CONVERGE"), std::string::npos);
}

TEST(StabilityRun, AnInversionTheModelAllowsEndsNothing) {
  std::optional<SceneDef> soft;
  for (const StressScene& s : stress_scenes())
    if (s.name == "stress-soft") {
      std::string error;
      soft = load_stress_scene(s, &error);
      ASSERT_TRUE(soft) << error;
    }
  ASSERT_TRUE(soft);
  SceneDef s = *soft;
  ASSERT_EQ(apply_method(*find_method("stable-neo-hookean"), s, true), "");
  EXPECT_TRUE(inversion_allowed(*find_method("stable-neo-hookean")));
  EXPECT_FALSE(inversion_allowed(*find_method("mass-spring"))) << "the springs' lesson";
  EXPECT_FALSE(inversion_allowed(*find_method("lecture")));
  RunOptions o;
  o.duration = 1.0;
  const RunResult failed = run_scene(s, o);
  EXPECT_EQ(failed.verdict, Verdict::Inverted);
  o.inversion_allowed = true;
  const RunResult allowed = run_scene(s, o);
  EXPECT_EQ(allowed.verdict, Verdict::InvertedAllowed) << allowed.message;
  EXPECT_EQ(allowed.fail_step, failed.fail_step) << "when it first inverted";
  EXPECT_EQ(allowed.steps, step_count(o.duration, s.h)) << "and the run went on to its end";
  EXPECT_LE(allowed.min_det_f, 0.0);
}

}  // namespace
}  // namespace invfree
