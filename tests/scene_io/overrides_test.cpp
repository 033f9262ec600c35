// --set overrides applied together (scene_io/scene_file.h's apply_overrides) and the
// reader's one rule per value type (issue 31 items 10 and 11): a scene that is valid only
// after several overrides is reached in any order; an error still names the --set it
// blames and leaves the scene as it was; integer keys read 4.0 alike everywhere; a number
// beyond a double's range and a body placed beyond double precision are called what they are.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"

namespace invfree {
namespace {

SceneDef builtin(const std::string& name) {
  const SceneLoad load = load_builtin_scene(name);
  EXPECT_TRUE(load.scene) << load.error;
  return load.scene ? *load.scene : SceneDef{};
}

std::string apply_all(SceneDef& s, const std::vector<std::string>& overrides) {
  return apply_overrides(s, overrides);
}

TEST(Overrides, ABoxIsValidatedOnceBothCornersAreSetInEitherOrder) {
  for (const bool min_first : {true, false}) {
    SceneDef s = builtin("course-3-contact");
    const std::string lo = "fixed.box_min=[-10,-10]", hi = "fixed.box_max=[10,10]";
    const std::vector<std::string> overrides =
        min_first ? std::vector<std::string>{lo, hi} : std::vector<std::string>{hi, lo};
    EXPECT_EQ(apply_all(s, overrides), "") << (min_first ? "min first" : "max first");
    EXPECT_TRUE(s.has_fixed);
    EXPECT_EQ(s.fixed_box_min, Vec2(-10.0, -10.0));
    EXPECT_EQ(s.fixed_box_max, Vec2(10.0, 10.0));
  }
}

TEST(Overrides, ATermAndTheKeyThatMakesItValidGoTogether) {
  SceneDef s = builtin("course-3-contact");
  EXPECT_EQ(apply_all(s, {"fixed.enabled=true", "fixed.corners=top"}), "");
  EXPECT_TRUE(s.has_fixed);
  EXPECT_EQ(s.fixed_corners, FixedCorners::Top);
}

TEST(Overrides, SelfContactIsJudgedOnTheFinalScene) {
  // Asked for together with the removal of the springs that would rule it out.
  SceneDef s = builtin("course-3-contact");
  EXPECT_EQ(apply_all(s, {"self_contact.enabled=true", "mass_spring.enabled=false"}), "");
  EXPECT_TRUE(s.self_contact_on());
  SceneDef t = builtin("course-3-contact");
  const std::string e = apply_all(t, {"self_contact.enabled=true"});
  EXPECT_EQ(e.rfind("--set self_contact.enabled=true: self_contact.enabled: is not available", 0),
            0u)
      << e;
}

TEST(Overrides, AnInvalidResultNamesTheSetItBlamesAndChangesNothing) {
  SceneDef s = builtin("compress");
  const SceneDef before = s;
  const std::string e = apply_all(s, {"time.h=0.02", "material.nu=0.45", "ceiling.stop=-2"});
  EXPECT_EQ(e.rfind("--set ceiling.stop=-2: ", 0), 0u) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  EXPECT_TRUE(s == before);
  // A value wrong on its own is refused by its own --set, whatever follows.
  const std::string bad = apply_all(s, {"time.h=-1", "time.h=0.01"});
  EXPECT_EQ(bad.rfind("--set time.h=-1: time.h: ", 0), 0u) << bad;
  EXPECT_TRUE(s == before);
}

TEST(Overrides, OneOverrideIsTheSameAsApplyOverride) {
  SceneDef a = builtin("compress"), b = builtin("compress");
  EXPECT_EQ(apply_override(a, "mesh.n_seg=6"), apply_all(b, {"mesh.n_seg=6"}));
  EXPECT_TRUE(a == b);
  EXPECT_EQ(apply_override(a, "fixed.box_min=[-10,-10]"),
            apply_all(b, {"fixed.box_min=[-10,-10]"}));
}

TEST(IntegerKeys, OneRuleInSectionsBodiesAndSet) {
  // A whole number written as a float is that integer, in [mesh] and in [[body]] alike.
  for (const char* text : {"[mesh]\nn_seg = 4.0\n", "[mesh]\nn_seg = 1e1\n",
                           "[[body]]\nn_seg = 4.0\n", "[[body]]\nn_seg = 1e1\n"}) {
    const SceneLoad load = parse_scene_toml(text, "ints.toml");
    ASSERT_TRUE(load.scene) << text << load.error;
    const int n = load.scene->bodies.empty() ? load.scene->n_seg : *load.scene->bodies[0].n_seg;
    EXPECT_EQ(n, std::string(text).find("1e1") != std::string::npos ? 10 : 4) << text;
  }
  // Not a whole number: refused alike.
  for (const char* text : {"[mesh]\nn_seg = 2.5\n", "[[body]]\nn_seg = 2.5\n"}) {
    const SceneLoad load = parse_scene_toml(text, "ints.toml");
    ASSERT_FALSE(load.scene) << text;
    EXPECT_NE(load.error.find("n_seg: expected an integer, got a number"), std::string::npos)
        << load.error;
  }
  SceneDef s = builtin("compress");
  EXPECT_EQ(apply_override(s, "mesh.n_seg=8.0"), "");
  EXPECT_EQ(s.n_seg, 8);
}

TEST(Overrides, ANumberBeyondADoubleIsCalledThat) {
  SceneDef s = builtin("compress");
  for (const char* o : {"mesh.side=1e400", "gravity.g=[0, -1e400]", "mesh.n_seg=-1e999"}) {
    const std::string e = apply_override(s, o);
    EXPECT_NE(e.find("is beyond a double's range"), std::string::npos) << o << ": " << e;
    EXPECT_NE(e.find("must be a finite number"), std::string::npos) << e;
    EXPECT_EQ(e.find("got a string"), std::string::npos) << e;
  }
  // A bare word still stands for a string.
  EXPECT_NE(apply_override(s, "time.h=fast").find("time.h: expected a number, got a string"),
            std::string::npos);
}

TEST(BodyOffset, FarBeyondDoublePrecisionIsBlamedOnTheOffset) {
  const SceneLoad load = parse_scene_toml(
      "[[body]]\noffset = [0.0, 0.0]\n[[body]]\noffset = [1.7e308, 0.0]\n",
      "far.toml");
  ASSERT_FALSE(load.scene);
  EXPECT_EQ(load.error.rfind("far.toml:4: body.offset: [[body]] 2 at [1.7e+308, 0]", 0), 0u)
      << load.error;
  EXPECT_EQ(load.error.find("mesh.side"), std::string::npos) << load.error;
  // A body that is itself too small is still the side's fault.
  const SceneLoad tiny = parse_scene_toml("[mesh]\nside = 1e-200\n", "tiny.toml");
  ASSERT_FALSE(tiny.scene);
  EXPECT_NE(tiny.error.find("mesh.side"), std::string::npos) << tiny.error;
}

}  // namespace
}  // namespace invfree
