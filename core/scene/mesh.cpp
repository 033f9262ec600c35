#include "scene/mesh.h"

namespace invfree {

Mesh square_mesh(double side, int n_seg) {
  Mesh mesh;
  const int n = n_seg + 1;
  const double step = side / n_seg;
  mesh.rest.reserve(static_cast<size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      mesh.rest.emplace_back(-0.5 * side + i * step, -0.5 * side + j * step);
  mesh.triangles.reserve(2 * static_cast<size_t>(n_seg) * n_seg);
  for (int i = 0; i < n_seg; ++i) {
    for (int j = 0; j < n_seg; ++j) {
      const int a = i * n + j, b = (i + 1) * n + j, c = (i + 1) * n + j + 1, d = i * n + j + 1;
      if ((i % 2) ^ (j % 2)) {
        mesh.triangles.push_back({a, b, d});
        mesh.triangles.push_back({b, c, d});
      } else {
        mesh.triangles.push_back({a, b, c});
        mesh.triangles.push_back({a, c, d});
      }
    }
  }
  compute_rest_data(mesh);
  return mesh;
}

void compute_rest_data(Mesh& mesh) {
  const size_t nt = mesh.triangles.size();
  mesh.rest_area.resize(nt);
  mesh.rest_shape_inverse.resize(nt);
  for (size_t t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    Mat2 basis;
    basis.col(0) = mesh.rest[tri[1]] - mesh.rest[tri[0]];
    basis.col(1) = mesh.rest[tri[2]] - mesh.rest[tri[0]];
    mesh.rest_area[t] = 0.5 * basis.determinant();
    mesh.rest_shape_inverse[t] = basis.inverse();
  }
}

std::vector<double> node_masses(const Mesh& mesh, double density, MassMode mode) {
  std::vector<double> mass(mesh.rest.size(), 0.0);
  double total_area = 0.0;
  for (double a : mesh.rest_area) total_area += a;
  if (mode == MassMode::Uniform) {
    const double m = density * total_area / static_cast<double>(mesh.rest.size());
    for (double& v : mass) v = m;
  } else {
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
      for (int k : mesh.triangles[t]) mass[k] += density * mesh.rest_area[t] / 3.0;
  }
  return mass;
}

int append_body(Mesh& all, const Mesh& body, const Vec2& offset) {
  const int first = all.node_count();
  for (const Vec2& x : body.rest) all.rest.push_back(x + offset);
  for (const auto& tri : body.triangles)
    all.triangles.push_back({tri[0] + first, tri[1] + first, tri[2] + first});
  all.rest_area.insert(all.rest_area.end(), body.rest_area.begin(), body.rest_area.end());
  all.rest_shape_inverse.insert(all.rest_shape_inverse.end(), body.rest_shape_inverse.begin(),
                                body.rest_shape_inverse.end());
  return first;
}

}  // namespace invfree
