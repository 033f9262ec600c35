// Half-space contact terms of the reference demo, per node, as functions of the signed
// gap d to a plane (ground y = y0 with normal +y, or the ceiling with normal -y).
//
// IPC log barrier (Li et al. 2020, "Incremental Potential Contact", eq. 6), scaled as in
// the demo by the node's contact area a and dhat:
//   b(d) = a dhat kappa/2 (s - 1) ln s,  s = d / dhat, for 0 < d < dhat; 0 beyond.
//   b'(d) = a kappa/2 (ln s + 1 - 1/s) <= 0,   b''(d) = a kappa/(2 dhat) (1/s + 1/s^2) > 0.
//
// Lagged IPC friction (IPC eq. 14-16) on a horizontal plane: tangential displacement
// u = x - x^n, normal force lambda = -b'(d^n) frozen at the step start, and the C1
// mollifier f0 with eps_u = eps_v h:
//   f0(y) = y (y >= eps_u),  -y^3/(3 eps_u^2) + y^2/eps_u + eps_u/3 (y < eps_u)
//   D(u) = mu_f lambda f0(|u|),  D'(u) = mu_f lambda f1(|u|) sign(u),
//   D''(u) = mu_f lambda (2/eps_u - 2|u|/eps_u^2) for |u| < eps_u, else 0  (>= 0).
#pragma once

#include <cmath>
#include <limits>

namespace invfree {

constexpr double kFrictionEpsV = 1e-3;  // m/s, the demo's eps_v

struct BarrierParams {
  double dhat = 0.01;
  double kappa = 1e5;
  double area = 0.25;  // contact area per node
};

inline double barrier_value(double d, const BarrierParams& b) {
  if (!(d > 0.0)) return std::numeric_limits<double>::infinity();
  if (d >= b.dhat) return 0.0;
  const double s = d / b.dhat;
  return b.area * b.dhat * 0.5 * b.kappa * (s - 1.0) * std::log(s);
}

inline double barrier_derivative(double d, const BarrierParams& b) {
  if (d >= b.dhat) return 0.0;
  const double s = d / b.dhat;
  return b.area * 0.5 * b.kappa * (std::log(s) + 1.0 - 1.0 / s);
}

inline double barrier_second_derivative(double d, const BarrierParams& b) {
  if (d >= b.dhat) return 0.0;
  const double s = d / b.dhat;
  return b.area * 0.5 * b.kappa / b.dhat * (1.0 / s + 1.0 / (s * s));
}

// The body's push on a ceiling at height ceiling_y (N, >= 0): the sum of the barrier's
// forces -b'(d) over the nodes closer than dhat below it. x: 2 per node (x, y).
inline double ceiling_push(const double* x, int nodes, double ceiling_y, const BarrierParams& b) {
  double push = 0.0;
  for (int i = 0; i < nodes; ++i) {
    const double d = ceiling_y - x[2 * i + 1];
    if (d > 0.0 && d < b.dhat) push -= barrier_derivative(d, b);
  }
  return push;
}

inline double friction_value(double u, double weight, double eps_u) {
  const double y = std::abs(u);
  if (y >= eps_u) return weight * y;
  return weight * (-y * y * y / (3.0 * eps_u * eps_u) + y * y / eps_u + eps_u / 3.0);
}

inline double friction_derivative(double u, double weight, double eps_u) {
  const double y = std::abs(u);
  if (y >= eps_u) return weight * (u > 0.0 ? 1.0 : -1.0);
  return weight * u * (2.0 / eps_u - y / (eps_u * eps_u));
}

inline double friction_second_derivative(double u, double weight, double eps_u) {
  const double y = std::abs(u);
  if (y >= eps_u) return 0.0;
  return weight * (2.0 / eps_u - 2.0 * y / (eps_u * eps_u));
}

}  // namespace invfree
