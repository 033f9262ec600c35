// The square mesh of the lecture's `square_mesh` code and its per-triangle rest data.
// Inputs: side length L, segments per side n_seg. Output: nodes numbered
// i*(n_seg+1)+j at (-L/2 + i L/n_seg, -L/2 + j L/n_seg), two triangles per cell in the
// alternating pattern of the slide, and per triangle the rest area and
// [X2-X1, X3-X1]^-1 (the lecture's IB).
#pragma once

#include <array>
#include <vector>

#include "types.h"

namespace invfree {

enum class MassMode {
  Uniform,  // total mass / node count (the reference demo's convention)
  Lumped    // one third of each triangle's mass to each of its nodes
};

struct Mesh {
  std::vector<Vec2> rest;  // X, one per node
  std::vector<std::array<int, 3>> triangles;
  std::vector<double> rest_area;         // per triangle
  std::vector<Mat2> rest_shape_inverse;  // per triangle: [X2-X1, X3-X1]^-1
  // Several bodies (scene/scene_mesh.h): each body's first node and first triangle.
  std::vector<int> body_begin{0};
  std::vector<int> body_triangle_begin{0};
  int node_count() const { return static_cast<int>(rest.size()); }
  int triangle_count() const { return static_cast<int>(triangles.size()); }
};

Mesh square_mesh(double side, int n_seg);
// Fills rest_area and rest_shape_inverse from rest and triangles.
void compute_rest_data(Mesh& mesh);
std::vector<double> node_masses(const Mesh& mesh, double density, MassMode mode);

// Appends `body` to `all` with every node moved by `offset` (the body's placement in the
// scene; the rest shape is unchanged by a translation) and returns the index of its first
// node, the value to list in body_begin.
int append_body(Mesh& all, const Mesh& body, const Vec2& offset);

}  // namespace invfree
