// Elasticity: sum_t area_t Psi(F_t) over the mesh's triangles, for the scene's material
// model (core/material/: Psi, P = dPsi/dF and the projected dP/dF per model, the
// per-triangle chain rule in triangle_elasticity.h), and its largest feasible step, the
// inversion-free filter of lecture 9 ("Inversion-Free Line Search Filtering").
// A whole-mesh term (term.h) of kind Elastic: its energy sums over blocks of triangles,
// its derivatives over colours of triangles that share no node (no locks), its filter is
// the inversion-free step; the per-range pieces for one model type M are below.
#pragma once

#include <algorithm>
#include <array>
#include <span>

#include "linalg/sparse_hessian.h"
#include "material/models.h"
#include "potential/term.h"
#include "material/triangle_elasticity.h"
#include "scene/mesh.h"

namespace invfree {

struct Elasticity {
  static constexpr EnergyKind kind = EnergyKind::Elastic;
  static constexpr bool scaled_by_h2 = true;
  Model model = Model::NeoHookean;
  Lame lame;
  HessianProjection projection = HessianProjection::Diagonal;
  bool inversion_filter = true;  // bound steps so that no triangle inverts (when det F > 0 is
                                 // required by the model)
  bool on = true;                // off for a mass-spring scene: no triangle term at all
  // Per triangle, when bodies of the scene have their own materials (scene/scene_mesh.h);
  // nullptr: `lame` for every triangle.
  const Lame* triangle_lame = nullptr;
  const Lame& lame_of(int t) const { return triangle_lame ? triangle_lame[t] : lame; }
  bool filters_inversions() const {
    return on && inversion_filter && !model_allows_inversion(model);
  }

  double value(const TermPoint& at, double scale) const;
  void add_derivatives(const TermPoint& at, double scale, Assembly& out) const;
  double max_step(const TermPoint& at, const VecX& dir, double alpha) const;
  void add_explicit_force(const TermPoint& at, VecX& gradient) const;
};

inline Mat2 triangle_deformation_gradient(const Mesh& mesh, const double* x, int t) {
  const auto& tri = mesh.triangles[t];
  auto node = [x](int i) { return Vec2(x[2 * i], x[2 * i + 1]); };
  return deformation_gradient(node(tri[0]), node(tri[1]), node(tri[2]), mesh.rest_shape_inverse[t]);
}

// sum of area_t Psi(F_t) over triangles [begin, end); triangle_lame as Elasticity's.
template <class M>
double elastic_energy_range(const Mesh& mesh, const Lame& lame, const double* x, int begin, int end,
                            const Lame* triangle_lame = nullptr) {
  double e = 0.0;
  for (int t = begin; t < end; ++t)
    e += mesh.rest_area[t] * M::energy_density(triangle_deformation_gradient(mesh, x, t),
                                               triangle_lame ? triangle_lame[t] : lame);
  return e;
}

// Adds scale * the gradient and projected Hessian of triangles [begin, end) into g and
// the fixed pattern of `hess` (its per-triangle slots).
template <class M>
void add_elastic_derivatives_range(const Mesh& mesh, const Elasticity& e, const double* x,
                                   int begin, int end, double scale, double* g,
                                   SparseHessian& hess) {
  double* values = hess.values();
  Vec6 gt;
  Mat6 ht;
  for (int t = begin; t < end; ++t) {
    const auto& tri = mesh.triangles[t];
    TriangleElasticity<M>::gradient_hessian(triangle_deformation_gradient(mesh, x, t),
                                            mesh.rest_shape_inverse[t], scale * mesh.rest_area[t],
                                            e.lame_of(t), e.projection, gt, ht);
    for (int a = 0; a < 3; ++a) {
      g[2 * tri[a]] += gt[2 * a];
      g[2 * tri[a] + 1] += gt[2 * a + 1];
    }
    const int* slots = &hess.triangle_slots[36 * static_cast<size_t>(t)];
    const double* local = ht.data();  // column-major; ht is symmetric, so row-major alike
    for (int k = 0; k < 36; ++k) values[slots[k]] += local[k];
  }
}

// The whole mesh, serially (explicit integration, energy bookkeeping, tests);
// triangle_lame as Elasticity's (empty: `lame` everywhere).
double elastic_energy(const Mesh& mesh, Model model, const Lame& lame, const VecX& x,
                      std::span<const Lame> triangle_lame = {});
// Adds scale * the elastic gradient to `gradient` (2N entries); no Hessian.
void add_elastic_gradient(const Mesh& mesh, Model model, const Lame& lame, const VecX& x,
                          double scale, VecX& gradient, std::span<const Lame> triangle_lame = {});

// The inversion-free filter: the largest alpha in (0, 1] that keeps every triangle's
// signed area above kMinAreaFraction of its current value along direction p (the
// quadratic a alpha^2 + b alpha + 0.9 = 0 in alpha, normalised by the current area).
constexpr double kMinAreaFraction = 0.1;
double inversion_free_step(const Mesh& mesh, const VecX& x, const VecX& p);
double signed_area(const VecX& x, const std::array<int, 3>& triangle);

// Smallest strictly positive real root of a t^2 + b t + c = 0, or +infinity when there is
// none. Uses the cancellation-free form of the quadratic formula and treats a == 0 and
// b == 0 exactly (the coefficients are already dimensionless, so no tolerance is needed).
double smallest_positive_root(double a, double b, double c);

}  // namespace invfree
