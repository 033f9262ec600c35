// Self-contact on by default (issue 30): every scene has it where it can run (not with
// springs or fixed nodes: scene.h's self_contact_can_run; a symplectic scene file keeps it
// off unless it asks, self_contact_by_default), asking for it where it cannot is a one-line
// error, and a scene whose boundary never comes within dhat of itself runs bit-identically
// with it on and off (the clearance certificate, potential/self_contact_clearance.h).
#include <gtest/gtest.h>

#include <string>

#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "simulation.h"
#include "solver/step_workspace.h"

namespace invfree {
namespace {

SceneDef builtin(const std::string& name) {
  SceneLoad load = load_builtin_scene(name);
  for (const auto& e : stress_scene_files())  // and `invfree stability`'s
    if (e.name == name) load = parse_scene_toml(e.text, name + ".toml");
  EXPECT_TRUE(load.scene) << name << ": " << load.error;
  return load.scene ? *load.scene : SceneDef{};
}

TEST(SelfContactDefault, OnInEveryBuiltinSceneThatCanRunIt) {
  EXPECT_TRUE(SceneDef{}.has_self_contact);
  EXPECT_TRUE(SceneDef{}.self_contact_on());
  int on = 0;
  for (const auto& e : builtin_scenes()) {
    const SceneDef s = builtin(std::string(e.name));
    // Only the terms it cannot run with, and the explicit integrator, switch it off.
    EXPECT_EQ(s.has_self_contact, self_contact_by_default(s)) << e.name;
    EXPECT_EQ(s.self_contact_on(), s.has_self_contact) << e.name;
    on += s.self_contact_on();
  }
  EXPECT_GT(on, 10);
  for (const char* name : {"compress", "drop", "course-9-affine", "course-9-modal", "bunny"})
    EXPECT_TRUE(builtin(name).self_contact_on()) << name;
  // The course's springs and fixed nodes, chapter 0's explicit steps: off.
  for (const char* name : {"course-0-free-fall", "course-0-mass-spring", "course-1-mass-spring",
                           "course-2-dirichlet", "course-5-moving-dirichlet", "modes-cantilever"})
    EXPECT_FALSE(builtin(name).has_self_contact) << name;
}

TEST(SelfContactDefault, AskedForWhereItCannotRunIsAOneLineError) {
  EXPECT_EQ(parse_scene_toml("[mass_spring]\n[self_contact]\nenabled = true\n", "s.toml").error,
            "s.toml:3: self_contact.enabled: is not available with [mass_spring] (springs need a "
            "fixed Hessian pattern)");
  EXPECT_EQ(
      parse_scene_toml("[fixed]\ncorners = \"top\"\n[self_contact]\nfriction = 0.2\n", "s.toml")
          .error,
      "s.toml:3: self_contact.enabled: is not available with [fixed] (fixed nodes need a "
      "fixed Hessian pattern)");
  // Symplectic Euler: off unless asked for; asked for, its intersection check runs.
  const SceneLoad explicit_off =
      parse_scene_toml("[solver]\nintegrator = \"symplectic-euler\"\n", "s.toml");
  ASSERT_TRUE(explicit_off.scene) << explicit_off.error;
  EXPECT_FALSE(explicit_off.scene->self_contact_on());
  const SceneLoad explicit_on =
      parse_scene_toml("[solver]\nintegrator = \"symplectic-euler\"\n[self_contact]\n", "s.toml");
  ASSERT_TRUE(explicit_on.scene) << explicit_on.error;
  EXPECT_TRUE(explicit_on.scene->self_contact_on());
  // Switched off, the same files load.
  EXPECT_TRUE(parse_scene_toml("[mass_spring]\n[self_contact]\nenabled = false\n", "s.toml").scene);
  SceneDef course = builtin("course-1-mass-spring");
  EXPECT_EQ(apply_override(course, "self_contact.enabled=true"),
            "--set self_contact.enabled=true: self_contact.enabled: is not available with "
            "[mass_spring] (springs need a fixed Hessian pattern)");
  EXPECT_FALSE(course.has_self_contact);
}

TEST(SelfContactDefault, ATermItCannotRunWithLeavesItInactive) {
  // compress asks for self-contact by default; --set adding springs or fixed nodes is
  // accepted, and self-contact is then off (and written so).
  for (const char* change : {"mass_spring.enabled=true", "fixed.corners=top"}) {
    SceneDef s = builtin("compress");
    ASSERT_EQ(apply_override(s, change), "") << change;
    EXPECT_FALSE(s.self_contact_on()) << change;
    const std::string text = scene_to_toml(s);
    EXPECT_NE(text.find("[self_contact]\nenabled = false\n"), std::string::npos) << text;
    const SceneLoad again = parse_scene_toml(text, "again.toml");
    ASSERT_TRUE(again.scene) << change << ": " << again.error;
    EXPECT_FALSE(again.scene->self_contact_on());
  }
  // The explicit integrator keeps it asked for: its intersection check then runs.
  SceneDef s = builtin("compress");
  ASSERT_EQ(apply_override(s, "solver.integrator=symplectic-euler"), "");
  EXPECT_TRUE(s.self_contact_on());
  // A scene file of a course scene writes what it reads back.
  const SceneDef course = builtin("course-3-contact");
  const SceneLoad again = parse_scene_toml(scene_to_toml(course), "course.toml");
  ASSERT_TRUE(again.scene) << again.error;
  EXPECT_TRUE(*again.scene == course);
}

// Runs the scene with self-contact on (its default) and off: the same bits, and the "on"
// run never grew the Hessian's pattern (no pair came within its dhat).
void expect_identical_with_and_without(SceneDef scene, int steps, const std::string& what) {
  ASSERT_TRUE(scene.self_contact_on()) << what;
  Simulation on = make_simulation(scene);
  scene.has_self_contact = false;
  Simulation off = make_simulation(scene);
  for (int k = 1; k <= steps; ++k) {
    const StepReport a = step(on), b = step(off);
    ASSERT_EQ(a.status, StepStatus::Ok) << what << " step " << k << ": " << a.message;
    ASSERT_EQ(b.status, StepStatus::Ok) << what << " step " << k << ": " << b.message;
    ASSERT_EQ(a.newton_iterations, b.newton_iterations) << what << " step " << k;
    ASSERT_TRUE(on.x == off.x) << what << ": positions differ after step " << k;
  }
  EXPECT_TRUE(on.v == off.v) << what;
  EXPECT_EQ(on.workspace->newton.hessian.pattern_version, 0) << what;
}

TEST(SelfContactDefault, TheLectureDemoIsBitIdenticalWithAndWithout) {
  for (int n_seg : {4, 8, 16}) {
    SceneDef s = builtin("compress");
    s.n_seg = n_seg;
    expect_identical_with_and_without(s, 300, "compress n_seg " + std::to_string(n_seg));
  }
}

TEST(SelfContactDefault, ScenesThatStayApartAreBitIdenticalWithAndWithout) {
  struct Case {
    const char* scene;
    int steps;
  };
  for (const Case c :
       {Case{"drop", 200}, Case{"course-9-affine", 100}, Case{"course-9-quadratic", 100},
        Case{"course-9-cubic", 100}, Case{"course-9-modal", 100}, Case{"course-3-contact", 50},
        Case{"stress-h0.1", 60}, Case{"stress-stiff", 100}, Case{"stress-nu0.49", 100},
        Case{"stress-jitter", 100}}) {
    SceneDef s = builtin(c.scene);
    if (!s.self_contact_on()) {  // course-3: springs; the same run twice, as it must be
      s.has_self_contact = true;
      EXPECT_FALSE(s.self_contact_on()) << c.scene;
      SceneDef off = s;
      off.has_self_contact = false;
      Simulation a = make_simulation(s), b = make_simulation(off);
      for (int k = 0; k < c.steps; ++k) {
        ASSERT_EQ(step(a).status, StepStatus::Ok);
        ASSERT_EQ(step(b).status, StepStatus::Ok);
      }
      EXPECT_TRUE(a.x == b.x) << c.scene;
      continue;
    }
    expect_identical_with_and_without(s, c.steps, c.scene);
  }
}

}  // namespace
}  // namespace invfree
