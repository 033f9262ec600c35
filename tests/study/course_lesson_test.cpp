// The lesson the stability table takes from the course: under the squash the mass-spring
// square inverts and the neo-Hookean one does not. Runs the `mass-spring` and `lecture`
// methods (methods.h) on the stability sweep's own scenes (the course's chapter-5 squash and
// the 10% squash) as the sweep does, and checks the verdicts against the kept frames' det F.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "app/study/methods.h"
#include "app/study/run.h"
#include "app/study/stability.h"
#include "app/study/stress_scenes.h"

namespace invfree {
namespace {

SceneDef sweep_scene(const std::string& name) {
  for (const StressScene& s : stress_scenes())
    if (s.name == name) {
      std::string error;
      auto scene = load_stress_scene(s, &error);
      EXPECT_TRUE(scene) << error;
      return scene ? *scene : SceneDef{};
    }
  ADD_FAILURE() << name << " is not a column of the stability table";
  return SceneDef{};
}

RunResult run_with(const char* method, SceneDef scene) {
  EXPECT_EQ(apply_method(*find_method(method), scene, true), "");
  RunOptions options;
  options.duration = stability_duration(scene);
  options.keep_frame = true;
  return run_scene(scene, options);
}

double min_det_f(const RunResult& r) {
  return *std::min_element(r.frame.det_f.begin(), r.frame.det_f.end());
}

TEST(CourseLesson, UnderTheSquashSpringsInvertAndNeoHookeanDoesNot) {
  for (const char* name : {"course-5-moving-dirichlet", "stress-squash10"}) {
    const SceneDef scene = sweep_scene(name);
    ASSERT_TRUE(scene.has_ceiling) << name;
    const RunResult springs = run_with("mass-spring", scene);
    EXPECT_EQ(springs.verdict, Verdict::Inverted) << name << ": " << springs.message;
    ASSERT_FALSE(springs.frame.det_f.empty()) << name;
    EXPECT_LE(min_det_f(springs), 0.0) << name << ": the failing frame shows the inversion";
    const RunResult neo = run_with("lecture", scene);
    EXPECT_EQ(neo.verdict, Verdict::Ok) << name << ": " << neo.message;
    EXPECT_EQ(neo.steps, step_count(stability_duration(scene), scene.h)) << name;
    ASSERT_FALSE(neo.frame.det_f.empty()) << name;
    EXPECT_GT(min_det_f(neo), 0.0) << name;
  }
}

TEST(CourseLesson, ItIsTheSquashThatInvertsTheSprings) {
  // The same chapter-5 square without the ceiling lands and rests on the ground uninverted,
  // so the mass-spring row's failure is the squash's, not the drop's.
  SceneDef scene = sweep_scene("course-5-moving-dirichlet");
  ASSERT_TRUE(scene.has_mass_spring) << "chapter 5 is the course's mass-spring square";
  scene.has_ceiling = false;
  const RunResult springs = run_with("mass-spring", scene);
  EXPECT_EQ(springs.verdict, Verdict::Ok) << springs.message;
  ASSERT_FALSE(springs.frame.det_f.empty());
  EXPECT_GT(min_det_f(springs), 0.0);
}

}  // namespace
}  // namespace invfree

namespace invfree {
namespace {

// The course's chapter 0 in the stability table: its explicit integrator is ok on the
// hanging mass-spring square at the demo's h (omega_max h = 0.83) and fails at h = 0.03 s
// (omega_max h = 2.5 > 2), and the table shows that verdict.
TEST(CourseLesson, ChapterZerosExplicitStepFailsWhenTooLarge) {
  const auto rows = explicit_rows();
  ASSERT_EQ(rows.size(), 2u);
  StabilityResult result;
  for (const ExplicitRow& row : rows) {
    EXPECT_EQ(std::string(row.scene), "course-0-mass-spring");
    result.explicit_cells.push_back(run_explicit_row(row, true));
  }
  const StabilityCell &small = result.explicit_cells[0], &large = result.explicit_cells[1];
  EXPECT_EQ(small.verdict, Verdict::Ok) << small.message;
  EXPECT_LT(rows[0].omega_h, 2.0);
  EXPECT_GT(rows[1].omega_h, 2.0);
  EXPECT_NE(large.verdict, Verdict::Ok);
  EXPECT_NE(large.verdict, Verdict::NotApplicable) << large.message;
  EXPECT_GT(large.fail_step, 0);
  EXPECT_EQ(large.method, "chapter-0-explicit-h0.03");
  const std::string md = stability_markdown(result);
  EXPECT_NE(md.find("| chapter-0-explicit-h0.01 | `course-0-mass-spring` | 0.01 s | 0.83 | ok |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| chapter-0-explicit-h0.03 | `course-0-mass-spring` | 0.03 s | 2.50 | **" +
                    std::string(verdict_name(large.verdict)) + "** ("),
            std::string::npos)
      << md;
  EXPECT_NE(stability_csv(result).find("chapter-0-explicit-h0.03,course-0-mass-spring," +
                                       std::string(verdict_name(large.verdict)) + "," +
                                       std::to_string(large.fail_step) + ","),
            std::string::npos);
}

}  // namespace
}  // namespace invfree
