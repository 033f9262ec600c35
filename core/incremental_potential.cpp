#include "core/incremental_potential.h"

#include <cmath>
#include <limits>

#include "core/models.h"
#include "core/triangle_elasticity.h"

namespace invfree {

namespace {

Vec2 node(const VecX& x, int i) { return x.segment<2>(2 * i); }

Mat2 triangle_f(const Mesh& mesh, const VecX& x, int t) {
  const auto& tri = mesh.triangles[t];
  return deformation_gradient(node(x, tri[0]), node(x, tri[1]), node(x, tri[2]),
                              mesh.rest_shape_inverse[t]);
}

template <class M>
double elastic_energy_for(const Mesh& mesh, const Lame& lame, const VecX& x) {
  double e = 0.0;
  for (int t = 0; t < mesh.triangle_count(); ++t)
    e += mesh.rest_area[t] * M::energy_density(triangle_f(mesh, x, t), lame);
  return e;
}

template <class M>
void add_elastic_gradient_for(const Mesh& mesh, const Lame& lame, const VecX& x, double scale,
                              VecX& g) {
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Mat46 dFdx = deformation_gradient_jacobian(mesh.rest_shape_inverse[t]);
    const Vec6 gt = TriangleElasticity<M>::gradient(triangle_f(mesh, x, t), dFdx,
                                                    scale * mesh.rest_area[t], lame);
    const auto& tri = mesh.triangles[t];
    for (int a = 0; a < 3; ++a) g.segment<2>(2 * tri[a]) += gt.segment<2>(2 * a);
  }
}

template <class M>
void add_elastic_hessian_for(const Mesh& mesh, const Lame& lame, HessianProjection projection,
                             const VecX& x, double scale, SparseHessian& hess) {
  double* values = hess.values();
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Mat46 dFdx = deformation_gradient_jacobian(mesh.rest_shape_inverse[t]);
    const Mat6 ht = TriangleElasticity<M>::hessian(triangle_f(mesh, x, t), dFdx,
                                                   scale * mesh.rest_area[t], lame, projection);
    const int* slots = &hess.triangle_slots[36 * static_cast<size_t>(t)];
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) values[slots[6 * a + b]] += ht(a, b);
  }
}

}  // namespace

double elastic_energy(const Mesh& mesh, Model model, const Lame& lame, const VecX& x) {
  return visit_model(model, [&](auto m) { return elastic_energy_for<decltype(m)>(mesh, lame, x); });
}

void add_elastic_gradient(const Mesh& mesh, Model model, const Lame& lame, const VecX& x,
                          double scale, VecX& gradient) {
  visit_model(model, [&](auto m) {
    add_elastic_gradient_for<decltype(m)>(mesh, lame, x, scale, gradient);
  });
}

double ip_energy(const StepProblem& p, const VecX& z) {
  const int n = p.node_count();
  const auto& mass = *p.mass;
  const double h2 = p.h * p.h;
  double inertia = 0.0;
  for (int i = 0; i < n; ++i)
    inertia += 0.5 * mass[i] * (z.segment<2>(2 * i) - p.x_tilde.segment<2>(2 * i)).squaredNorm();

  double potential = elastic_energy(*p.mesh, p.model, p.lame, z.head(2 * n));
  if (p.gravity_on)
    for (int i = 0; i < n; ++i) potential -= mass[i] * p.gravity.dot(z.segment<2>(2 * i));
  if (p.ground_on)
    for (int i = 0; i < n; ++i) potential += barrier_value(z[2 * i + 1] - p.ground_y, p.barrier);
  if (p.friction_on)
    for (int i = 0; i < n; ++i)
      if (p.friction_weight[i] > 0.0)
        potential += friction_value(z[2 * i] - p.x_start[2 * i], p.friction_weight[i], p.friction_eps_u);
  double penalty = 0.0;
  if (p.ceiling_on) {
    const double c = z[2 * n];
    for (int i = 0; i < n; ++i) potential += barrier_value(c - z[2 * i + 1], p.barrier);
    penalty = 0.5 * p.ceiling_stiffness * (c - p.ceiling_target) * (c - p.ceiling_target);
  }
  const double e = inertia + h2 * potential + penalty;
  return std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
}

void ip_gradient_hessian(const StepProblem& p, const VecX& z, VecX& g, SparseHessian& hess) {
  const int n = p.node_count();
  const auto& mass = *p.mass;
  const double h2 = p.h * p.h;
  g.setZero(p.dof_count());
  hess.set_zero();
  double* values = hess.values();
  const auto& diag = hess.diagonal_slots;

  for (int i = 0; i < n; ++i) {
    g.segment<2>(2 * i) = mass[i] * (z.segment<2>(2 * i) - p.x_tilde.segment<2>(2 * i));
    values[diag[2 * i]] += mass[i];
    values[diag[2 * i + 1]] += mass[i];
  }
  visit_model(p.model, [&](auto m) {
    using M = decltype(m);
    const VecX x = z.head(2 * n);
    add_elastic_gradient_for<M>(*p.mesh, p.lame, x, h2, g);
    add_elastic_hessian_for<M>(*p.mesh, p.lame, p.projection, x, h2, hess);
  });
  if (p.gravity_on)
    for (int i = 0; i < n; ++i) g.segment<2>(2 * i) -= h2 * mass[i] * p.gravity;
  if (p.ground_on)
    for (int i = 0; i < n; ++i) {
      const double d = z[2 * i + 1] - p.ground_y;
      if (d >= p.barrier.dhat) continue;
      g[2 * i + 1] += h2 * barrier_derivative(d, p.barrier);
      values[diag[2 * i + 1]] += h2 * barrier_second_derivative(d, p.barrier);
    }
  if (p.friction_on)
    for (int i = 0; i < n; ++i) {
      const double w = p.friction_weight[i];
      if (w <= 0.0) continue;
      const double u = z[2 * i] - p.x_start[2 * i];
      g[2 * i] += h2 * friction_derivative(u, w, p.friction_eps_u);
      values[diag[2 * i]] += h2 * friction_second_derivative(u, w, p.friction_eps_u);
    }
  if (p.ceiling_on) {
    const int c = 2 * n;
    for (int i = 0; i < n; ++i) {
      const double d = z[c] - z[2 * i + 1];
      if (d >= p.barrier.dhat) continue;
      // b(c - y_i): d/dc = b', d/dy_i = -b'; Hessian b'' [1 -1; -1 1] on (y_i, c).
      const double d1 = h2 * barrier_derivative(d, p.barrier);
      const double d2 = h2 * barrier_second_derivative(d, p.barrier);
      g[2 * i + 1] -= d1;
      g[c] += d1;
      values[diag[2 * i + 1]] += d2;
      values[diag[c]] += d2;
      values[hess.ceiling_slots[2 * i]] -= d2;
      values[hess.ceiling_slots[2 * i + 1]] -= d2;
    }
    g[c] += p.ceiling_stiffness * (z[c] - p.ceiling_target);
    values[diag[c]] += p.ceiling_stiffness;
    if (p.ceiling_fixed) {
      g[c] = 0.0;
      hess.eliminate_ceiling();
    }
  }
}

}  // namespace invfree
