#include "core/scene_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace invfree {
namespace {

TEST(SceneFiles, EveryBuiltinHasAnIdenticalAssetFile) {
  for (const auto& entry : builtin_scenes()) {
    const std::string path = std::string(INVFREE_SOURCE_DIR) + "/assets/scenes/" + entry.name + ".toml";
    const SceneLoad load = load_scene(path);
    ASSERT_TRUE(load.scene) << load.error;
    EXPECT_TRUE(*load.scene == entry.make()) << entry.name << " differs from " << path;
  }
}

TEST(SceneFiles, SerialisationRoundTrips) {
  for (const auto& entry : builtin_scenes()) {
    SceneDef s = entry.make();
    s.jitter = 0.1;
    s.seed = 42;
    s.initial_velocity = Vec2(1.0, -20.0);
    s.projection = HessianProjection::Full;
    const SceneLoad back = parse_scene_toml(scene_to_toml(s), "roundtrip.toml");
    ASSERT_TRUE(back.scene) << back.error;
    EXPECT_TRUE(*back.scene == s) << scene_to_toml(s);
  }
}

TEST(SceneFiles, MissingSectionsSwitchTermsOff) {
  const SceneLoad load = parse_scene_toml("[mesh]\nn_seg = 2\n", "bare.toml");
  ASSERT_TRUE(load.scene) << load.error;
  EXPECT_FALSE(load.scene->has_gravity);
  EXPECT_FALSE(load.scene->has_ground);
  EXPECT_FALSE(load.scene->has_ceiling);
  EXPECT_EQ(load.scene->name, "bare");
}

TEST(SceneFiles, YoungPoissonOrLame) {
  auto a = parse_scene_toml("[material]\nE = 1e4\nnu = 0.3\n", "a.toml");
  ASSERT_TRUE(a.scene);
  EXPECT_DOUBLE_EQ(a.scene->lame.mu, 1e4 / 2.6);
  auto b = parse_scene_toml("[material]\nmu = 10\nlambda = 20\n", "b.toml");
  ASSERT_TRUE(b.scene);
  EXPECT_EQ(b.scene->lame, (Lame{10, 20}));
}

struct BadCase {
  const char* text;
  const char* expected;  // substring of the one-line error
};

TEST(SceneFiles, BadInputGivesOneLineErrorsNamingFileLineAndKey) {
  const BadCase cases[] = {
      {"[material]\nnu = 0.5\n", "bad.toml:2: material.nu: must be in [0, 0.5)"},
      {"[material]\nnu = -0.1\n", "material.nu: must be in [0, 0.5)"},
      {"[material]\nE = 0\n", "bad.toml:2: material.E: must be > 0"},
      {"[material]\nE = -5\n", "material.E: must be > 0"},
      {"[material]\nE = 1e5\nmu = 3\n", "give either E and nu or mu and lambda"},
      {"[material]\nmodel = \"neohookean\"\n", "material.model: unknown value \"neohookean\""},
      {"[time]\nh = 0\n", "bad.toml:2: time.h: must be a finite number > 0"},
      {"[time]\nh = -0.01\n", "time.h: must be a finite number > 0"},
      {"[time]\nh = nan\n", "time.h: must be a finite number"},
      {"[time]\nh = \"fast\"\n", "time.h: expected a number, got a string"},
      {"[mesh]\nn_seg = 0\n", "bad.toml:2: mesh.n_seg: must be between 1 and 1024"},
      {"[mesh]\nn_seg = 2.5\n", "mesh.n_seg: expected an integer"},
      {"[mesh]\nnseg = 4\n", "bad.toml:2: mesh.nseg: unknown key (did you mean \"n_seg\"?)"},
      {"[mesh]\ndensity = 0\n", "mesh.density: must be a finite number > 0"},
      {"[meshh]\nn_seg = 4\n", "meshh: unknown section (did you mean \"mesh\"?)"},
      {"[ground]\ny = 0.0\n", "ground.y: the square starts on or through the ground"},
      {"[ceiling]\ny = 0.2\n", "ceiling.y: the square starts on or through the ceiling"},
      {"[ground]\ny = -1\n[ceiling]\ny = -2\n", "ceiling.y: must be above ground.y"},
      {"[ground]\ny = -1\nfriction = -0.1\n", "ground.friction: must be a finite number >= 0"},
      {"[ground]\ny = -1\n[barrier]\ndhat = 0\n", "barrier.dhat: must be a finite number > 0"},
      {"[ground]\ny = -1\n[barrier]\nkappa = -1\n", "barrier.kappa: must be a finite number > 0"},
      {"[gravity]\ng = [0, 1, 2]\n", "gravity.g: expected an array of two numbers"},
      {"[mesh]\njitter = 0.45\nn_seg = 8\n", "mesh.jitter: the initial mesh has an inverted triangle"},
      {"[mesh\nn_seg = 4\n", "bad.toml:1: malformed TOML"},
      {"n_seg = 4\n", "n_seg: unknown top-level key"},
      {"mesh = 3\n", "mesh: expected a [mesh] section"},
  };
  for (const auto& c : cases) {
    const SceneLoad load = parse_scene_toml(c.text, "bad.toml");
    ASSERT_FALSE(load.scene) << c.text;
    EXPECT_NE(load.error.find(c.expected), std::string::npos) << "got: " << load.error;
    EXPECT_EQ(load.error.find('\n'), std::string::npos) << load.error;
  }
  EXPECT_NE(parse_scene_toml(std::string("[mesh]\0\x01\x02", 9), "bin.toml").error.find("not a text file"),
            std::string::npos);
}

TEST(SceneFiles, MissingFileAndUnknownName) {
  const SceneLoad load = load_scene("/nonexistent/scene.toml");
  ASSERT_FALSE(load.scene);
  EXPECT_NE(load.error.find("no readable file"), std::string::npos);
}

TEST(Overrides, ApplyAndValidate) {
  SceneDef s = *find_builtin_scene("compress");
  EXPECT_EQ(apply_override(s, "material.E=1e4"), "");
  double E, nu;
  young_poisson_from_lame(s.lame, &E, &nu);
  EXPECT_NEAR(E, 1e4, 1e-8);
  EXPECT_NEAR(nu, 0.4, 1e-12);
  EXPECT_EQ(apply_override(s, "material.model=linear"), "");
  EXPECT_EQ(s.model, Model::Linear);
  EXPECT_EQ(apply_override(s, "ceiling.enabled=false"), "");
  EXPECT_FALSE(s.has_ceiling);
  EXPECT_EQ(apply_override(s, "ceiling.y=0.8"), "");
  EXPECT_TRUE(s.has_ceiling);
  EXPECT_EQ(apply_override(s, "gravity.g=[0, -1.62]"), "");
  EXPECT_DOUBLE_EQ(s.gravity.y(), -1.62);

  const SceneDef before = s;
  EXPECT_NE(apply_override(s, "material.nu=0.5").find("material.nu: must be in [0, 0.5)"), std::string::npos);
  EXPECT_NE(apply_override(s, "time.h=0").find("time.h"), std::string::npos);
  EXPECT_NE(apply_override(s, "time.hh=0.1").find("did you mean \"h\""), std::string::npos);
  EXPECT_NE(apply_override(s, "timing.h=0.1").find("unknown section"), std::string::npos);
  EXPECT_NE(apply_override(s, "time.h").find("expected section.key=value"), std::string::npos);
  EXPECT_NE(apply_override(s, "ground.y=0").find("ground.y"), std::string::npos);
  EXPECT_TRUE(s == before) << "a rejected override must leave the scene unchanged";
  SceneDef drop = *find_builtin_scene("drop");
  EXPECT_NE(apply_override(drop, "ground.y=0").find("through the ground"), std::string::npos);
}

}  // namespace
}  // namespace invfree
