#include "scene/scene_mesh.h"

#include <algorithm>

#include "scene/boundary.h"
#include "shape/shape_mesh.h"
#include "shape/shape_region.h"

namespace invfree {

Mesh body_mesh(const PlacedBody& b) {
  if (b.shape.kind == ShapeKind::Square) return square_mesh(b.side, b.n_seg);
  // find_scene_problem has meshed the shape already (the mesher caches its last results);
  // a shape it refused never gets here.
  return mesh_shape(b.shape, shape_max_edge(b.shape, b.n_seg)).mesh;
}

Mesh scene_mesh(const SceneDef& scene) {
  const int bodies = body_count(scene);
  if (bodies == 1 && placed_body(scene, 0).offset == Vec2::Zero())
    return body_mesh(placed_body(scene, 0));
  Mesh all;
  all.body_begin.clear();
  all.body_triangle_begin.clear();
  for (int k = 0; k < bodies; ++k) {
    const PlacedBody b = placed_body(scene, k);
    all.body_triangle_begin.push_back(all.triangle_count());
    all.body_begin.push_back(append_body(all, body_mesh(b), b.offset));
  }
  return all;
}

bool scene_has_only_squares(const SceneDef& scene) {
  for (int k = 0; k < body_count(scene); ++k)
    if (placed_body(scene, k).shape.kind != ShapeKind::Square) return false;
  return true;
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
  // [mesh] node_mass: every node the same mass (particles have no area to weigh).
  if (scene.node_mass > 0.0) return std::vector<double>(mesh.rest.size(), scene.node_mass);
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
  if (!scene_has_only_squares(scene)) {
    // A meshed shape's boundary node stands for half of each of its two boundary edges (the
    // square's side / n_seg on a grid); an interior node for none: it never reaches a plane
    // before the boundary around it does. A square body keeps the tutorial's value, and so
    // does a particle (shape "points": its body's edge length, it has no boundary).
    std::vector<double> area(mesh.rest.size(), 0.0);
    const Boundary boundary = find_boundary(mesh);
    for (int k = 0; k < boundary.node_count(); ++k) area[boundary.nodes[k]] = boundary.node_area[k];
    for (int k = 0; k < bodies; ++k)
      if (const ShapeKind kind = placed_body(scene, k).shape.kind;
          kind == ShapeKind::Square || kind == ShapeKind::Points)
        std::fill(area.begin() + mesh.body_begin[k], area.begin() + body_node_end(mesh, k),
                  body_edge_length(scene, k));
    return area;
  }
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
