// The course scenes (assets/scenes/course-*.toml, stack.toml, stack-friction.toml) against the
// public solid-sim-tutorial's Python demos they come from. tests/data/course/<scene>.txt holds the
// demo's node positions every 10 steps over 200 steps, run converged (tol 1e-6) with its own
// settings (scripts/course_reference.py made them from the tutorial; tests/data/course/README.md
// says how). Each scene, also converged (tol 1e-6), must follow its demo at every sample, to
// 1e-4 m for chapters 1-8, 1e-6 m for chapter 9's polynomial bases and 1e-5 m for its modal
// basis (issue 29; why the modal one is looser: docs/scenes.md, "Reduced bases"), and also
// lets the picture move (a reference that stays still would match
// anything that does nothing). Samples stop where the ceiling does (stack, stack-friction:
// after 194 of the 200 steps): the demo decides by the ceiling's actual height, invfree by
// its nominal one, so the demo moves it once more (docs/method.md, "Where the ceiling
// stops"), a deliberate difference of one 5 mm step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "scene_io/builtin_scenes.h"
#include "simulation.h"
#include "tests/simulation/course_reference.h"

namespace invfree {
namespace {

struct CourseCase {
  const char* scene;
  double tolerance;  // m
};

class CourseScene : public ::testing::TestWithParam<CourseCase> {};

TEST_P(CourseScene, FollowsThePythonDemo) {
  const std::string name = GetParam().scene;
  const double tolerance = GetParam().tolerance;
  const auto reference = test::read_course_reference(name);
  ASSERT_EQ(reference.size(), 21u) << "tests/data/course/" << name << ".txt";
  SceneLoad load = load_builtin_scene(name);
  ASSERT_TRUE(load.scene) << load.error;
  SceneDef scene = *load.scene;
  scene.tol = 1e-6;  // converged, as the reference was run
  Simulation sim = make_simulation(scene);
  ASSERT_EQ(sim.x.size(), static_cast<long>(reference[0].x.size()));
  // The last step whose start the ceiling's nominal height is still above its stop.
  long last_step = reference.back().step;
  if (scene.has_ceiling && scene.ceiling_velocity < 0.0)
    last_step = std::min(
        last_step,
        static_cast<long>(std::ceil(
            (scene.ceiling_y - scene.ceiling_stop) / (-scene.ceiling_velocity * scene.h) - 1e-9)));
  double worst = 0.0, moved = 0.0;
  for (const test::CourseSample& sample : reference) {
    if (sample.step > last_step) break;
    while (sim.step_count < sample.step) {
      const StepReport r = step(sim);
      ASSERT_EQ(r.status, StepStatus::Ok)
          << name << " step " << sim.step_count << ": " << r.message;
    }
    for (size_t k = 0; k < sample.x.size(); ++k) {
      worst = std::max(worst, std::abs(sim.x[k] - sample.x[k]));
      moved = std::max(moved, std::abs(sample.x[k] - reference[0].x[k]));
    }
    EXPECT_LT(worst, tolerance) << name << " at step " << sample.step;
    if (worst >= tolerance) break;
  }
  EXPECT_GT(moved, 0.05) << name << ": the reference hardly moves";
  std::ostringstream text;
  text << worst;
  RecordProperty("max_difference_m", text.str());
}

INSTANTIATE_TEST_SUITE_P(Course, CourseScene,
                         ::testing::Values(CourseCase{"course-1-mass-spring", 1e-4},
                                           CourseCase{"course-2-dirichlet", 1e-4},
                                           CourseCase{"course-3-contact", 1e-4},
                                           CourseCase{"course-4-friction", 1e-4},
                                           CourseCase{"course-5-moving-dirichlet", 1e-4},
                                           CourseCase{"stack", 1e-4},
                                           CourseCase{"stack-friction", 1e-4},
                                           CourseCase{"course-9-affine", 1e-6},
                                           CourseCase{"course-9-quadratic", 1e-6},
                                           CourseCase{"course-9-cubic", 1e-6},
                                           CourseCase{"course-9-modal", 1e-5}),
                         [](const auto& info) {
                           std::string n = info.param.scene;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

}  // namespace
}  // namespace invfree
