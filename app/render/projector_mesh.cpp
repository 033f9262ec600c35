#include "app/render/projector_mesh.h"

#include <algorithm>

namespace invfree::render {

bool refine_for_projector(SceneDef& scene, int min_n_seg) {
  if (min_n_seg <= 0 || scene.n_seg >= min_n_seg) return false;
  if (!scene.has_triangle_elasticity() || scene.reduced_basis != ReducedBasis::Full ||
      scene.shape.kind != ShapeKind::Square)
    return false;
  for (const BodyDef& b : scene.bodies)
    if (b.n_seg || (b.shape && *b.shape != ShapeKind::Square)) return false;
  SceneDef finer = scene;
  finer.n_seg = min_n_seg;
  if (!validate_scene(finer).empty()) return false;
  scene = std::move(finer);
  return true;
}

bool overrides_set_n_seg(const std::vector<std::string>& overrides) {
  for (const std::string& o : overrides) {
    std::string key = o.substr(0, o.find('='));
    key.erase(std::remove_if(key.begin(), key.end(), [](char c) { return c == ' ' || c == '\t'; }),
              key.end());
    if (key == "mesh.n_seg") return true;
  }
  return false;
}

}  // namespace invfree::render
