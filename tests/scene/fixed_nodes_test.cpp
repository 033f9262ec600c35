// Fixed nodes are chosen by rules in rest space (scene/fixed_nodes.h), so a rule holds the
// same places whatever the mesh's resolution.
#include "scene/fixed_nodes.h"

#include <gtest/gtest.h>

#include <set>

namespace invfree {
namespace {

std::set<std::pair<double, double>> places(const SceneDef& s) {
  const Mesh mesh = square_mesh(s.side, s.n_seg);
  std::set<std::pair<double, double>> out;
  for (int i : select_fixed_nodes(s, mesh)) out.insert({mesh.rest[i].x(), mesh.rest[i].y()});
  return out;
}

TEST(FixedNodes, CornerRulesHoldTheSamePlacesAtEveryResolution) {
  SceneDef s;
  s.has_fixed = true;
  s.fixed_corners = FixedCorners::Top;
  for (int n : {1, 2, 4, 7, 16}) {
    s.n_seg = n;
    EXPECT_EQ(places(s), (std::set<std::pair<double, double>>{{-0.5, 0.5}, {0.5, 0.5}})) << n;
  }
  s.fixed_corners = FixedCorners::All;
  s.n_seg = 7;
  EXPECT_EQ(places(s).size(), 4u);
}

TEST(FixedNodes, ABoxTakesEveryNodeInsideItAtAnyResolution) {
  SceneDef s;
  s.has_fixed = true;
  s.fixed_box_min = Vec2(-0.6, 0.45);  // the top row
  s.fixed_box_max = Vec2(0.6, 0.6);
  for (int n : {2, 4, 7}) {
    s.n_seg = n;
    const auto p = places(s);
    EXPECT_EQ(p.size(), static_cast<size_t>(n + 1)) << n;
    for (const auto& [x, y] : p) EXPECT_EQ(y, 0.5) << n;
  }
}

}  // namespace
}  // namespace invfree
