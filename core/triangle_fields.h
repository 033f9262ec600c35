// What the lecture computes per triangle, read off a simulation's current state: a field
// over the triangles to colour them by (det F, the energy density Psi, the signed largest
// principal Cauchy stress, the number of dP/dF eigenvalues the PSD projection clamps), the
// triangle under a point of the deformed body, and one triangle's whole analysis
// (material/stress_analysis.h) with its own model and Lame parameters.
#pragma once

#include <optional>
#include <vector>

#include "enum_names.h"
#include "material/stress_analysis.h"
#include "simulation.h"

namespace invfree {

// The colourings `render --color-by` and the live panel offer.
enum class TriangleField {
  DetF,     // area now / area at rest (dimensionless)
  Psi,      // energy density, Pa = J/m^3
  Stress,   // the principal Cauchy stress of largest magnitude, signed: tension > 0 (Pa)
  Clamped,  // how many of dP/dF's four eigenvalues the projection sets to zero (0..4)
};
inline constexpr EnumName<TriangleField> kTriangleFieldNames[] = {
    {TriangleField::DetF, "det-f"},
    {TriangleField::Psi, "psi"},
    {TriangleField::Stress, "stress"},
    {TriangleField::Clamped, "clamped"}};

// The field's value per triangle into *out (resized). Mass-spring scenes have no
// deformation energy per triangle: Psi, stress and clamped are 0 there (det F is still
// geometry).
void triangle_field(const Simulation& sim, TriangleField field, std::vector<double>* out);

// A triangle of the deformed mesh that contains `point` (m; on an edge counts), the one
// with the smallest index where triangles overlap (a fold) or share the point; either
// orientation (an inverted triangle is clockwise); never a degenerate one. nullopt when
// none does, or the point is not finite.
std::optional<int> triangle_at(const Simulation& sim, const Vec2& point);

// The triangle's own material (a body may have its own Lame parameters).
Lame triangle_material(const Simulation& sim, int triangle);
Mat2 triangle_deformation_gradient(const Simulation& sim, int triangle);

// The lecture's quantities for one triangle (its F, its model, its Lame parameters). Only
// for scenes with triangle elasticity (scene.has_triangle_elasticity()).
StressAnalysis analyze_triangle(const Simulation& sim, int triangle);

}  // namespace invfree
