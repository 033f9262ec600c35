// The course's chapter 0 (solid-sim-tutorial 0_getting_started: explicit symplectic Euler)
// against its three Python demos: tests/data/course/course-0-*.txt hold the demos' node
// positions (scripts/course_reference.py runs simulator0/1/2.py as they are, recording at
// the top of every loop iteration): the free fall every step until the demo's own stop at
// y <= -1 (step 45), the spring and the mass-spring square every 10 steps over 200 steps.
// Each scene must follow its demo to 1e-6 m at every sample (explicit steps have no
// tolerance: the differences are rounding). Also: the mass-spring square's per-spring
// gravity (simulator2.py's quirk) is what makes it match; particles without triangles run
// under implicit Euler (Newton) too; and bad chapter-0 input is a one-line error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "energy_report.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "simulation.h"
#include "tests/simulation/course_reference.h"

namespace invfree {
namespace {

SceneDef course_scene(const std::string& name) {
  SceneLoad load = load_builtin_scene(name);
  EXPECT_TRUE(load.scene) << load.error;
  return load.scene ? *load.scene : SceneDef{};
}

// The largest |x - reference| over every sample, stepping `scene` alongside.
double max_difference(const SceneDef& scene, const std::vector<test::CourseSample>& reference) {
  Simulation sim = make_simulation(scene);
  EXPECT_EQ(sim.x.size(), static_cast<long>(reference.at(0).x.size()));
  double worst = 0.0;
  for (const test::CourseSample& sample : reference) {
    while (sim.step_count < sample.step) {
      const StepReport r = step(sim);
      EXPECT_EQ(r.status, StepStatus::Ok)
          << scene.name << " step " << sim.step_count << ": " << r.message;
      if (r.status != StepStatus::Ok) return INFINITY;
    }
    for (size_t k = 0; k < sample.x.size(); ++k)
      worst = std::max(worst, std::abs(sim.x[k] - sample.x[k]));
  }
  return worst;
}

class CourseZero : public ::testing::TestWithParam<const char*> {};

TEST_P(CourseZero, FollowsThePythonDemoToAMicrometre) {
  const std::string name = GetParam();
  const auto reference = test::read_course_reference(name);
  // The free fall to the demo's stop (steps 0..45), the others 200 steps.
  ASSERT_EQ(reference.size(), name == "course-0-free-fall" ? 46u : 21u);
  EXPECT_EQ(reference.back().step, name == "course-0-free-fall" ? 45 : 200);
  double moved = 0.0;
  for (const test::CourseSample& s : reference)
    for (size_t k = 0; k < s.x.size(); ++k)
      moved = std::max(moved, std::abs(s.x[k] - reference[0].x[k]));
  EXPECT_GT(moved, 0.05) << name << ": the reference hardly moves";
  const double worst = max_difference(course_scene(name), reference);
  EXPECT_LE(worst, 1e-6) << name;
  std::ostringstream text;
  text << worst;
  RecordProperty("max_difference_m", text.str());
}

INSTANTIATE_TEST_SUITE_P(Course, CourseZero,
                         ::testing::Values("course-0-free-fall", "course-0-spring",
                                           "course-0-mass-spring"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

// simulator2.py adds h g inside its spring loop: a node gets g once per spring it ends.
// [gravity] per_spring = true reproduces it; gravity once per node differs by up to 1.08 m.
TEST(CourseZero, PerSpringGravityIsWhatMatchesSimulator2) {
  const auto reference = test::read_course_reference("course-0-mass-spring");
  SceneDef scene = course_scene("course-0-mass-spring");
  ASSERT_TRUE(scene.gravity_per_spring);
  EXPECT_LE(max_difference(scene, reference), 1e-6);
  scene.gravity_per_spring = false;
  const double once = max_difference(scene, reference);
  EXPECT_GT(once, 0.05);
  std::ostringstream text;
  text << once;
  RecordProperty("gravity_once_per_node_difference_m", text.str());
}

// The weight is the spring count: a corner of the 4x4 square ends 3 springs, an edge node
// 5, an interior node 8; the gravitational energy counts it too.
TEST(CourseZero, PerSpringGravityWeighsEachNodeByItsSprings) {
  SceneDef scene = course_scene("course-0-mass-spring");
  scene.initial_stretch = Vec2(1.0, 1.0);
  Simulation sim = make_simulation(scene);
  double expected = 0.0;
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    const int a = i / 5, b = i % 5;
    const int edges = (a > 0) + (a < 4) + (b > 0) + (b < 4);
    const int diagonals = (a > 0 && b > 0) + (a > 0 && b < 4) + (a < 4 && b > 0) + (a < 4 && b < 4);
    expected += -(edges + diagonals) * 1000.0 * (-10.0) * sim.x[2 * i + 1];
  }
  EXPECT_NEAR(energy_report(sim).gravitational, expected, 1e-9 * std::abs(expected) + 1e-9);
  scene.gravity_per_spring = false;
  sim = make_simulation(scene);
  double once = 0.0;
  for (int i = 0; i < sim.mesh.node_count(); ++i) once += 1000.0 * 10.0 * sim.x[2 * i + 1];
  EXPECT_NEAR(energy_report(sim).gravitational, once, 1e-9);
}

// Particles without triangles through Newton: under a constant force implicit Euler's
// update (v += h g, x += h v) is symplectic Euler's, so the free fall matches the demo
// under either integrator; the spring under implicit Euler stays finite and loses energy.
TEST(CourseZero, ParticlesRunUnderImplicitEulerToo) {
  SceneDef fall = course_scene("course-0-free-fall");
  fall.integrator = Integrator::ImplicitEuler;
  fall.tol = 1e-9;
  EXPECT_LE(max_difference(fall, test::read_course_reference("course-0-free-fall")), 1e-9);
  SceneDef spring = course_scene("course-0-spring");
  spring.integrator = Integrator::ImplicitEuler;
  spring.tol = 1e-6;
  Simulation sim = make_simulation(spring);
  const double start = total_energy(sim);
  for (int k = 0; k < 200; ++k) {
    const StepReport r = step(sim);
    ASSERT_EQ(r.status, StepStatus::Ok) << r.message;
  }
  EXPECT_TRUE(sim.x.allFinite());
  EXPECT_EQ(sim.x[0], 0.0);  // the origin is held
  EXPECT_EQ(sim.x[1], 0.0);
  EXPECT_LT(total_energy(sim), start);
}

// A scene file's chapter-0 mistakes are one line naming the key the file wrote.
TEST(CourseZero, BadInputIsOneLineNamingTheKey) {
  const std::string particles =
      "[mesh]\nshape = \"points\"\npoints = [[0.0, 0.0], [0.3, 0.0]]\nnode_mass = 1.0\n";
  const struct {
    std::string text, error;
  } cases[] = {
      {particles + "[mass_spring]\nsprings = [[0, 2]]\n",
       "bad.toml:6: mass_spring.springs: spring 0: node 2 is out of range (the mesh has 2 "
       "nodes)"},
      {particles + "[mass_spring]\nsprings = [[0, 1], [1, 1]]\n",
       "bad.toml:6: mass_spring.springs: spring 1: both ends are node 1"},
      {"[mesh]\nshape = \"points\"\npoints = [[0.0, 0.0], [0.0, 0.0]]\nnode_mass = 1.0\n"
       "[mass_spring]\nsprings = [[0, 1]]\n",
       "bad.toml:6: mass_spring.springs: spring 0: nodes 0 and 1 share a rest position (the "
       "green law divides by the rest length)"},
      {"[mesh]\nshape = \"points\"\npoints = [[0.0, 0.0]]\n[mass_spring]\n",
       "bad.toml:2: mesh.shape: shape \"points\" needs node_mass > 0 (a particle has no area to "
       "weigh)"},
      {particles,
       "bad.toml:2: mesh.shape: \"points\" has no triangles for [material]'s elasticity: add a "
       "[mass_spring] section (springs, or none for free particles)"},
      {"[mesh]\nshape = \"points\"\npoints = []\nnode_mass = 1.0\n[mass_spring]\n",
       "bad.toml:3: mesh.points: shape \"points\" needs at least one point"},
      {"[mesh]\nnode_mass = -1\n", "bad.toml:2: mesh.node_mass: must be a finite number >= 0"},
      {"[gravity]\nper_spring = true\n",
       "bad.toml:2: gravity.per_spring: counts springs: it needs [mass_spring]"},
      {"[mass_spring]\nlaw = \"linear\"\n",
       "bad.toml:2: mass_spring.law: unknown value \"linear\" (expected one of \"green\", "
       "\"hooke\")"},
      {"[mesh]\nshape = \"points\"\npoints = [[0.0, 0.0]]\nnode_mass = 1.0\n[mass_spring]\n"
       "[ground]\ny = -1\n",
       "bad.toml:3: mesh.points: a single point has no edge length for the barrier's contact area"},
  };
  for (const auto& c : cases) {
    const SceneLoad load = parse_scene_toml(c.text, "bad.toml");
    EXPECT_FALSE(load.scene) << c.text;
    EXPECT_NE(load.error.find(c.error), std::string::npos)
        << c.text << "\nexpected: " << c.error << "\ngot: " << load.error;
    EXPECT_EQ(load.error.find('\n'), std::string::npos) << load.error;
  }
  // Two particles 0.3 m apart do have an edge length (0.3 / n_seg): the ground is fine.
  EXPECT_TRUE(parse_scene_toml(particles + "[mass_spring]\n[ground]\ny = -1\n", "ok.toml").scene);
  // A Hooke spring may have a zero rest length (it pulls its ends together).
  EXPECT_TRUE(parse_scene_toml("[mesh]\nshape = \"points\"\npoints = [[0.0, 0.0], [0.0, 0.0]]\n"
                               "node_mass = 1.0\n[mass_spring]\nlaw = \"hooke\"\n"
                               "springs = [[0, 1]]\n",
                               "ok.toml")
                  .scene);
}

// The three scenes write and read back as they are (the springs' pairs included).
TEST(CourseZero, ScenesRoundTrip) {
  for (const char* name : {"course-0-free-fall", "course-0-spring", "course-0-mass-spring"}) {
    const SceneDef s = course_scene(name);
    const SceneLoad back = parse_scene_toml(scene_to_toml(s), "back.toml");
    ASSERT_TRUE(back.scene) << back.error;
    EXPECT_TRUE(*back.scene == s) << scene_to_toml(s);
  }
  const SceneDef spring = course_scene("course-0-spring");
  EXPECT_NE(scene_to_toml(spring).find("\nsprings = [[0, 1]]\n"), std::string::npos);
  EXPECT_NE(scene_to_toml(spring).find("\npoints = [[0.0, 0.0], [0.3, 0.0]]\n"), std::string::npos);
}

}  // namespace
}  // namespace invfree
