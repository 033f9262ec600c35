#include "triangle_fields.h"

#include "potential/elasticity.h"

namespace invfree {

Lame triangle_material(const Simulation& sim, int triangle) {
  return sim.triangle_lame.empty() ? sim.scene.lame : sim.triangle_lame[triangle];
}

Mat2 triangle_deformation_gradient(const Simulation& sim, int triangle) {
  return triangle_deformation_gradient(sim.mesh, sim.x.data(), triangle);
}

void triangle_field(const Simulation& sim, TriangleField field, std::vector<double>* out) {
  const int n = sim.mesh.triangle_count();
  out->resize(static_cast<size_t>(n));
  const bool elastic = sim.scene.has_triangle_elasticity();
  const Model model = sim.scene.model;
  for (int t = 0; t < n; ++t) {
    const Mat2 F = triangle_deformation_gradient(sim, t);
    double v = 0.0;
    switch (field) {
      case TriangleField::DetF:
        v = determinant(F);
        break;
      case TriangleField::Psi:
        if (elastic) v = energy_density_of(model, F, triangle_material(sim, t));
        break;
      case TriangleField::Stress:
        if (elastic) v = signed_max_principal_stress(model, F, triangle_material(sim, t));
        break;
      case TriangleField::Clamped:
        if (elastic) v = clamped_eigenvalue_count(model, F, triangle_material(sim, t));
        break;
    }
    (*out)[static_cast<size_t>(t)] = v;
  }
}

std::optional<int> triangle_at(const Simulation& sim, const Vec2& point) {
  // Every comparison with NaN is false: without this a NaN point would be "inside" the
  // first triangle (no sign disagrees).
  if (!point.allFinite()) return std::nullopt;
  const double* x = sim.x.data();
  for (int t = 0; t < sim.mesh.triangle_count(); ++t) {
    const auto& tri = sim.mesh.triangles[static_cast<size_t>(t)];
    const Vec2 a(x[2 * tri[0]], x[2 * tri[0] + 1]);
    const Vec2 b(x[2 * tri[1]], x[2 * tri[1] + 1]);
    const Vec2 c(x[2 * tri[2]], x[2 * tri[2] + 1]);
    // Barycentric signs: inside (or on an edge) when the three agree, whatever the
    // triangle's orientation (an inverted one is clockwise).
    const auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
    const double d0 = cross(b - a, point - a), d1 = cross(c - b, point - b),
                 d2 = cross(a - c, point - c);
    const bool has_neg = d0 < 0.0 || d1 < 0.0 || d2 < 0.0;
    const bool has_pos = d0 > 0.0 || d1 > 0.0 || d2 > 0.0;
    if (!(has_neg && has_pos) && cross(b - a, c - a) != 0.0) return t;
  }
  return std::nullopt;
}

StressAnalysis analyze_triangle(const Simulation& sim, int triangle) {
  return analyze_stress(sim.scene.model, triangle_deformation_gradient(sim, triangle),
                        triangle_material(sim, triangle));
}

}  // namespace invfree
