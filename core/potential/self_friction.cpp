#include "potential/self_friction.h"

#include <cmath>

namespace invfree {

void lag_self_friction(const Boundary& boundary, const std::vector<Vec2>& rest,
                       std::span<const PointEdgePair> pairs, const VecX& x_start,
                       const SelfContactParams& params, double mu,
                       std::vector<SelfFrictionPair>& out) {
  out.clear();
  if (!(mu > 0.0)) return;
  const double dhat2 = params.dhat * params.dhat;
  for (const PointEdgePair& pair : pairs) {
    const int i = boundary.nodes[pair.node];
    const auto& e = boundary.edges[pair.edge];
    const Vec2 p = x_start.segment<2>(2 * i), a = x_start.segment<2>(2 * e[0]),
               b = x_start.segment<2>(2 * e[1]);
    const PointEdgeRegime regime = point_edge_regime(p, a, b);
    const double d2 = point_edge_distance_squared(p, a, b, regime);
    if (!(d2 > 0.0) || d2 >= dhat2) continue;
    const BarrierParams barrier = pair_barrier(boundary, rest, pair, params);
    if (d2 >= barrier.dhat) continue;
    // lambda = -dB/dd = -B'(D) dD/dd = -B'(D) 2 d.
    const double d = std::sqrt(d2);
    const double lambda = -barrier_derivative(d2, barrier) * 2.0 * d;
    const double r = point_edge_closest_parameter(p, a, b, regime);
    const Vec2 normal = (p - ((1.0 - r) * a + r * b)) / d;
    out.push_back({{i, e[0], e[1]}, mu * lambda, r, Vec2(-normal.y(), normal.x())});
  }
}

double self_friction_energy(std::span<const SelfFrictionPair> pairs, const VecX& x,
                            const VecX& x_start, double eps_u) {
  double energy = 0.0;
  for (const SelfFrictionPair& f : pairs)
    energy += self_friction_value(f, pair_displacement(f, x, x_start), eps_u);
  return energy;
}

void add_self_friction_gradient_hessian(std::span<const SelfFrictionPair> pairs, const VecX& x,
                                        const VecX& x_start, double eps_u, double scale,
                                        VecX& gradient, std::vector<PointEdgeHessian>& hessians) {
  for (const SelfFrictionPair& f : pairs) {
    const Vec6 displacement = pair_displacement(f, x, x_start);
    const Vec6 g = self_friction_gradient(f, displacement, eps_u);
    for (int k = 0; k < 3; ++k) gradient.segment<2>(2 * f.nodes[k]) += scale * g.segment<2>(2 * k);
    const double curvature =
        friction_second_derivative(slip_direction(f).dot(displacement), f.weight, eps_u);
    if (curvature > 0.0)
      hessians.push_back({f.nodes, scale * self_friction_hessian(f, displacement, eps_u)});
  }
}

}  // namespace invfree
