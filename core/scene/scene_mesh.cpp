#include "scene/scene_mesh.h"

#include <algorithm>

namespace invfree {

Mesh scene_mesh(const SceneDef& scene) {
  const int bodies = body_count(scene);
  if (bodies == 1 && placed_body(scene, 0).offset == Vec2::Zero()) {
    const PlacedBody b = placed_body(scene, 0);
    return square_mesh(b.side, b.n_seg);
  }
  Mesh all;
  all.body_begin.clear();
  all.body_triangle_begin.clear();
  for (int k = 0; k < bodies; ++k) {
    const PlacedBody b = placed_body(scene, k);
    all.body_triangle_begin.push_back(all.triangle_count());
    all.body_begin.push_back(append_body(all, square_mesh(b.side, b.n_seg), b.offset));
  }
  return all;
}

int body_of_node(const Mesh& mesh, int node) {
  const auto it = std::upper_bound(mesh.body_begin.begin(), mesh.body_begin.end(), node);
  return static_cast<int>(it - mesh.body_begin.begin()) - 1;
}

namespace {
// [first node, end node) and [first triangle, end triangle) of body k.
int body_node_end(const Mesh& mesh, int k) {
  return k + 1 < static_cast<int>(mesh.body_begin.size()) ? mesh.body_begin[k + 1]
                                                          : mesh.node_count();
}
int body_triangle_end(const Mesh& mesh, int k) {
  return k + 1 < static_cast<int>(mesh.body_triangle_begin.size()) ? mesh.body_triangle_begin[k + 1]
                                                                   : mesh.triangle_count();
}
}  // namespace

std::vector<double> scene_node_masses(const SceneDef& scene, const Mesh& mesh) {
  if (mesh.body_begin.size() == 1) return node_masses(mesh, scene.density, scene.mass);
  std::vector<double> mass(mesh.rest.size(), 0.0);
  for (int k = 0; k < static_cast<int>(mesh.body_begin.size()); ++k) {
    const int n0 = mesh.body_begin[k], n1 = body_node_end(mesh, k);
    const int t0 = mesh.body_triangle_begin[k], t1 = body_triangle_end(mesh, k);
    double area = 0.0;
    for (int t = t0; t < t1; ++t) area += mesh.rest_area[t];
    if (scene.mass == MassMode::Uniform) {
      const double m = scene.density * area / static_cast<double>(n1 - n0);
      for (int i = n0; i < n1; ++i) mass[i] = m;
    } else {
      for (int t = t0; t < t1; ++t)
        for (int i : mesh.triangles[t]) mass[i] += scene.density * mesh.rest_area[t] / 3.0;
    }
  }
  return mass;
}

std::vector<double> scene_node_contact_areas(const SceneDef& scene, const Mesh& mesh) {
  const int bodies = body_count(scene);
  bool uniform = true;
  for (int k = 1; k < bodies; ++k)
    uniform = uniform && body_edge_length(scene, k) == body_edge_length(scene, 0);
  if (uniform) return {};
  std::vector<double> area(mesh.rest.size());
  for (int k = 0; k < bodies; ++k)
    std::fill(area.begin() + mesh.body_begin[k], area.begin() + body_node_end(mesh, k),
              body_edge_length(scene, k));
  return area;
}

std::vector<Lame> scene_triangle_lame(const SceneDef& scene, const Mesh& mesh) {
  const int bodies = body_count(scene);
  bool uniform = true;
  for (int k = 0; k < bodies; ++k) uniform = uniform && placed_body(scene, k).lame == scene.lame;
  if (uniform) return {};
  std::vector<Lame> lame(mesh.triangles.size());
  for (int k = 0; k < bodies; ++k)
    std::fill(lame.begin() + mesh.body_triangle_begin[k], lame.begin() + body_triangle_end(mesh, k),
              placed_body(scene, k).lame);
  return lame;
}

}  // namespace invfree
