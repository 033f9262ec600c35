// The initial state of scene/initial_state.h: every node starts with its body's velocity,
// whether the scene lists one [[body]] table or several (issue 31 item 5: one body ignored
// its own), and a scene without [[body]] tables takes initial.velocity.
#include <gtest/gtest.h>

#include <string>

#include "scene/initial_state.h"
#include "scene/scene_mesh.h"
#include "scene_io/scene_file.h"

namespace invfree {
namespace {

SceneDef scene_of(const std::string& text) {
  const SceneLoad load = parse_scene_toml(text, "initial.toml");
  EXPECT_TRUE(load.scene) << load.error;
  return load.scene ? *load.scene : SceneDef{};
}

// Every node of `scene` starts with `velocity`.
void expect_every_node_moves_at(const SceneDef& scene, const Vec2& velocity) {
  const Mesh mesh = scene_mesh(scene);
  const VecX v = initial_velocities(scene, mesh);
  ASSERT_EQ(v.size(), 2 * mesh.node_count());
  for (int i = 0; i < mesh.node_count(); ++i)
    EXPECT_EQ(Vec2(v.segment<2>(2 * i)), velocity) << "node " << i;
}

TEST(InitialVelocities, OneBodyTableKeepsItsOwnVelocity) {
  // At the origin (the mesh is the body's own) and moved (placed by offset): both paths.
  expect_every_node_moves_at(scene_of("[initial]\nvelocity = [0.5, 0.0]\n"
                                      "[[body]]\nvelocity = [0.0, -3.0]\n"),
                             Vec2(0.0, -3.0));
  expect_every_node_moves_at(scene_of("[[body]]\noffset = [0.2, 0.1]\nvelocity = [1.5, 2.0]\n"),
                             Vec2(1.5, 2.0));
}

TEST(InitialVelocities, OneBodyTableWithoutVelocityTakesTheScenes) {
  expect_every_node_moves_at(scene_of("[initial]\nvelocity = [0.5, -0.25]\n[[body]]\n"),
                             Vec2(0.5, -0.25));
}

TEST(InitialVelocities, WithoutBodyTablesTheSceneVelocity) {
  expect_every_node_moves_at(scene_of("[initial]\nvelocity = [0.0, -2.0]\n"), Vec2(0.0, -2.0));
}

TEST(InitialVelocities, EachOfSeveralBodiesHasItsOwn) {
  const SceneDef s = scene_of(
      "[initial]\nvelocity = [0.0, -1.0]\n"
      "[[body]]\nside = 0.4\noffset = [0.0, 0.0]\nvelocity = [2.0, 0.0]\n"
      "[[body]]\nside = 0.4\noffset = [1.0, 0.0]\n");
  const Mesh mesh = scene_mesh(s);
  const VecX v = initial_velocities(s, mesh);
  for (int i = 0; i < mesh.node_count(); ++i)
    EXPECT_EQ(Vec2(v.segment<2>(2 * i)), body_of_node(mesh, i) == 0 ? Vec2(2.0, 0.0)
                                                                     : Vec2(0.0, -1.0))
        << "node " << i;
}

}  // namespace
}  // namespace invfree
