// [[body]] tables (scene_io/body_tables.h): defaults from the scene, a body's own
// material, the round trip through scene_to_toml, and one-line errors with the line and
// the table's number.
#include <gtest/gtest.h>

#include <string>

#include "scene/scene_mesh.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"

namespace invfree {
namespace {

const char* kTwoBodies = R"(name = "two"
[mesh]
side = 0.5
n_seg = 3
[material]
E = 2e5
nu = 0.3
[initial]
velocity = [0.0, -1.0]
[[body]]
offset = [-1.0, 0.0]
[[body]]
side = 0.25
n_seg = 5
offset = [1.0, 0.5]
velocity = [2.0, 0.0]
E = 1e6
)";

TEST(BodyTables, UnsetValuesComeFromTheSceneAndOwnOnesStay) {
  const SceneLoad load = parse_scene_toml(kTwoBodies, "two.toml");
  ASSERT_TRUE(load.scene) << load.error;
  const SceneDef& s = *load.scene;
  ASSERT_EQ(body_count(s), 2);
  const PlacedBody a = placed_body(s, 0), b = placed_body(s, 1);
  EXPECT_EQ(a.side, 0.5);
  EXPECT_EQ(a.n_seg, 3);
  EXPECT_EQ(a.offset, Vec2(-1.0, 0.0));
  EXPECT_EQ(a.velocity, Vec2(0.0, -1.0));
  EXPECT_EQ(a.lame, lame_from_young_poisson(2e5, 0.3));
  EXPECT_EQ(b.side, 0.25);
  EXPECT_EQ(b.n_seg, 5);
  EXPECT_EQ(b.velocity, Vec2(2.0, 0.0));
  // E alone keeps the scene's nu, as in [material].
  EXPECT_EQ(b.lame, lame_from_young_poisson(1e6, 0.3));
}

TEST(BodyTables, TheMeshHoldsEveryBodyInOrderWithItsOwnMassAndArea) {
  const SceneLoad load = parse_scene_toml(kTwoBodies, "two.toml");
  ASSERT_TRUE(load.scene) << load.error;
  const Mesh mesh = scene_mesh(*load.scene);
  ASSERT_EQ(mesh.body_begin, (std::vector<int>{0, 16}));
  ASSERT_EQ(mesh.body_triangle_begin, (std::vector<int>{0, 18}));
  EXPECT_EQ(mesh.node_count(), 16 + 36);
  EXPECT_EQ(body_of_node(mesh, 15), 0);
  EXPECT_EQ(body_of_node(mesh, 16), 1);
  EXPECT_NEAR(mesh.rest[0].x(), -1.25, 1e-15);  // the first body's lower-left corner
  EXPECT_NEAR(mesh.rest[16].x(), 0.875, 1e-15);
  // Uniform masses per body: each body weighs density x its own area.
  const std::vector<double> m = scene_node_masses(*load.scene, mesh);
  double first = 0.0, second = 0.0;
  for (int i = 0; i < mesh.node_count(); ++i) (i < 16 ? first : second) += m[i];
  EXPECT_NEAR(first, 1000.0 * 0.25, 1e-9);
  EXPECT_NEAR(second, 1000.0 * 0.0625, 1e-9);
  // Edge lengths differ (1/6 m, 1/20 m): each node carries its body's plane-contact area.
  const std::vector<double> area = scene_node_contact_areas(*load.scene, mesh);
  ASSERT_EQ(area.size(), 52u);
  EXPECT_EQ(area[0], 0.5 / 3);
  EXPECT_EQ(area[51], 0.25 / 5);
  // The second body's own material reaches its triangles only.
  const std::vector<Lame> lame = scene_triangle_lame(*load.scene, mesh);
  ASSERT_EQ(lame.size(), 18u + 50u);
  EXPECT_EQ(lame[17], lame_from_young_poisson(2e5, 0.3));
  EXPECT_EQ(lame[18], lame_from_young_poisson(1e6, 0.3));
}

TEST(BodyTables, ASceneWithoutBodiesIsOneSquareAtTheOriginAsBefore) {
  const SceneLoad load = load_builtin_scene("compress");
  ASSERT_TRUE(load.scene) << load.error;
  EXPECT_TRUE(load.scene->bodies.empty());
  EXPECT_EQ(body_count(*load.scene), 1);
  const Mesh a = scene_mesh(*load.scene), b = square_mesh(1.0, 4);
  EXPECT_EQ(a.rest, b.rest);
  EXPECT_EQ(a.body_begin, std::vector<int>{0});
  EXPECT_TRUE(scene_node_contact_areas(*load.scene, a).empty());
  EXPECT_TRUE(scene_triangle_lame(*load.scene, a).empty());
}

TEST(BodyTables, RoundTripThroughSceneToToml) {
  for (const char* name : {"stack", "stack-friction"}) {
    const SceneLoad load = load_builtin_scene(name);
    ASSERT_TRUE(load.scene) << load.error;
    const SceneLoad back = parse_scene_toml(scene_to_toml(*load.scene), "back.toml");
    ASSERT_TRUE(back.scene) << back.error << "\n" << scene_to_toml(*load.scene);
    EXPECT_TRUE(*back.scene == *load.scene) << scene_to_toml(*load.scene);
  }
  const SceneLoad two = parse_scene_toml(kTwoBodies, "two.toml");
  ASSERT_TRUE(two.scene) << two.error;
  const SceneLoad back = parse_scene_toml(scene_to_toml(*two.scene), "back.toml");
  ASSERT_TRUE(back.scene) << back.error;
  EXPECT_TRUE(*back.scene == *two.scene) << scene_to_toml(*two.scene);
}

std::string error_of(const std::string& text) {
  const SceneLoad load = parse_scene_toml(text, "bad.toml");
  EXPECT_FALSE(load.scene) << text;
  EXPECT_EQ(load.error.find('\n'), std::string::npos) << load.error;
  return load.error;
}

TEST(BodyTables, BadTablesGetOneLineNamingTheKeyTheTableAndTheLine) {
  EXPECT_EQ(error_of("[mesh]\nn_seg = 2\n[[body]]\noffset = [0.0, 0.0]\n[[body]]\nn_seg = 0\n"),
            "bad.toml:6: body.n_seg: must be between 1 and 4096 (in [[body]] 2)");
  EXPECT_EQ(
      error_of("[[body]]\nofset = [1.0, 0.0]\n"),
      "bad.toml:2: body.ofset: unknown key (did you mean \"offset\"?) (keys of [[body]]: "
      "side, n_seg, shape, width, height, radius, inner_radius, outline, holes, file, path_id, "
      "scale, max_edge, offset, velocity, E, nu, mu, lambda)");
  EXPECT_EQ(error_of("[[body]]\noffset = [1.0]\n"),
            "bad.toml:2: body.offset: expected an array of two numbers, e.g. [0.0, -0.5] (in "
            "[[body]] 1)");
  EXPECT_EQ(error_of("[[body]]\nvelocity = [1.0, nan]\n"),
            "bad.toml:2: body.velocity: element 1: expected a finite number (in [[body]] 1)");
  EXPECT_EQ(error_of("[[body]]\nside = -1.0\n"),
            "bad.toml:2: body.side: must be a finite number > 0 (in [[body]] 1)");
  EXPECT_EQ(error_of("[[body]]\nE = 1e5\nmu = 1e4\n"),
            "bad.toml:2: body.E: give either E and nu or mu and lambda, not both (in [[body]] 1)");
  EXPECT_EQ(error_of("body = 3\n"),
            "bad.toml:1: body: expected [[body]] tables (an array of tables), got an integer");
  std::string many;
  for (int k = 0; k <= kMaxBodies; ++k)
    many += "[[body]]\noffset = [" + std::to_string(2 * k) + ".0, 0.0]\n";
  EXPECT_EQ(error_of(many), "bad.toml:1: body: at most 64 [[body]] tables, got 65");
}

TEST(BodyTables, BodiesThatOverlapAtTheStartAreRefusedWithSelfContact) {
  const std::string overlap =
      "[mesh]\nside = 0.5\n[self_contact]\n[[body]]\noffset = [0.0, 0.0]\n[[body]]\noffset = [0.3, "
      "0.1]\n";
  EXPECT_EQ(error_of(overlap),
            "bad.toml:7: body.offset: [[body]] 2 touches or overlaps [[body]] 1 at t = 0 "
            "(self-contact, on by default, needs them apart; self_contact.enabled = false lets "
            "them overlap)");
  // Self-contact is on without the section too.
  const std::string unsaid = overlap.substr(0, overlap.find("[self_contact]\n")) +
                             overlap.substr(overlap.find("[[body]]"));
  EXPECT_NE(error_of(unsaid).find("needs them apart"), std::string::npos);
  // Switched off, the bodies do not see each other and may overlap.
  const std::string off = overlap.substr(0, overlap.find("[[body]]")) + "enabled = false\n" +
                          overlap.substr(overlap.find("[[body]]"));
  const SceneLoad load = parse_scene_toml(off, "off.toml");
  EXPECT_TRUE(load.scene) << load.error;
}

}  // namespace
}  // namespace invfree
