// Lagged IPC friction between a boundary node and a boundary edge (the solid-sim-tutorial's
// 8_self_friction), the point-edge counterpart of the ground friction in
// potential/friction.h. Frozen at the step start x^n for each pair closer than its dhat:
//  - the normal force lambda = -dB/dd of the self-contact barrier (self_contact_barrier.h),
//  - the closest point's parameter r on the edge (a + r (b - a)) and the unit tangent t, the
//    normal n = (p - closest point) / d turned by +90 degrees.
// The slip is the node's displacement against the edge's point, along t:
//   u = t . [(p - p^n) - (1 - r)(a - a^n) - r (b - b^n)] = t . J (x - x^n),
//   J = [I, -(1 - r) I, -r I]  (2 x 6 over (p, a, b)),
// and the pair's dissipative potential is the ground's D(u) = mu lambda f0(|u|) with the same
// mollifier and eps_u = eps_v h (potential/friction.h). In 2D the tangent space is the
// line of t, so |T (relative displacement)| = |u|: gradient D'(u) J^T t, Hessian
// D''(u) (J^T t)(J^T t)^T, positive semi-definite as it stands (D'' >= 0).
// Inputs: candidate pairs at x^n (collision/broad_phase.h), x^n, the barrier's parameters,
// mu. Outputs: the lagged pairs; then value, gradient and Hessians at x.
#pragma once

#include <span>
#include <vector>

#include "potential/friction.h"
#include "potential/self_contact_barrier.h"

namespace invfree {

struct SelfFrictionPair {
  std::array<int, 3> nodes;  // mesh nodes: the point, edge[0], edge[1]
  double weight = 0.0;       // mu lambda (N)
  double r = 0.0;            // closest point a + r (b - a) at x^n, r in [0, 1]
  Vec2 tangent = Vec2::Zero();
};

// Replaces `out` by the pairs within their dhat at x_start, with weight mu lambda > 0.
void lag_self_friction(const Boundary& boundary, const std::vector<Vec2>& rest,
                       std::span<const PointEdgePair> pairs, const VecX& x_start,
                       const SelfContactParams& params, double mu,
                       std::vector<SelfFrictionPair>& out);

// J^T t over (p, a, b): u = slip_direction . (x - x^n) restricted to the pair's nodes.
inline Vec6 slip_direction(const SelfFrictionPair& f) {
  Vec6 s;
  s << f.tangent, -(1.0 - f.r) * f.tangent, -f.r * f.tangent;
  return s;
}

// The pair's nodes' displacements x - x^n, stacked (p, a, b).
inline Vec6 pair_displacement(const SelfFrictionPair& f, const VecX& x, const VecX& x_start) {
  Vec6 d;
  for (int k = 0; k < 3; ++k)
    d.segment<2>(2 * k) = x.segment<2>(2 * f.nodes[k]) - x_start.segment<2>(2 * f.nodes[k]);
  return d;
}

inline double self_friction_slip(const SelfFrictionPair& f, const VecX& x, const VecX& x_start) {
  return slip_direction(f).dot(pair_displacement(f, x, x_start));
}

// One pair as a function of its displacement (p, a, b) - (p^n, a^n, b^n).
inline double self_friction_value(const SelfFrictionPair& f, const Vec6& displacement,
                                  double eps_u) {
  return friction_value(slip_direction(f).dot(displacement), f.weight, eps_u);
}
inline Vec6 self_friction_gradient(const SelfFrictionPair& f, const Vec6& displacement,
                                   double eps_u) {
  const Vec6 s = slip_direction(f);
  return friction_derivative(s.dot(displacement), f.weight, eps_u) * s;
}
inline Mat6 self_friction_hessian(const SelfFrictionPair& f, const Vec6& displacement,
                                  double eps_u) {
  const Vec6 s = slip_direction(f);
  return friction_second_derivative(s.dot(displacement), f.weight, eps_u) * s * s.transpose();
}

double self_friction_energy(std::span<const SelfFrictionPair> pairs, const VecX& x,
                            const VecX& x_start, double eps_u);
// gradient += scale * dE/dx; appends scale * each pair's Hessian (zero ones skipped).
void add_self_friction_gradient_hessian(std::span<const SelfFrictionPair> pairs, const VecX& x,
                                        const VecX& x_start, double eps_u, double scale,
                                        VecX& gradient, std::vector<PointEdgeHessian>& hessians);

}  // namespace invfree
