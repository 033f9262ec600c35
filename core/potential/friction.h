// Lagged IPC friction on the ground (IPC eq. 14-16; the lecture demo's FrictionEnergy):
// tangential slip u = x_i - x_i^n along the plane, normal force lambda_i = -b'(d_i^n) frozen
// at the step's start, and the C1 mollifier f0 with eps_u = eps_v h:
//   f0(y) = y (y >= eps_u),  -y^3/(3 eps_u^2) + y^2/eps_u + eps_u/3 (y < eps_u)
//   D(u) = mu_f lambda f0(|u|),  D'(u) = mu_f lambda f1(|u|) sign(u),
//   D''(u) = mu_f lambda (2/eps_u - 2|u|/eps_u^2) for |u| < eps_u, else 0  (>= 0).
// The weight w_i = mu_f lambda_i is 0 for a node farther than dhat from the ground.
// Explicit integration uses the same law on the current slip h v with the current normal
// force (add_explicit_force).
// On a sloped ground the slip is u = t.(x_i - x_i^n) along the plane's unit tangent t,
// gradient D'(u) t and Hessian D''(u) t t^T (the tutorial's T = I - n n^T in 2D); the
// horizontal ground keeps u = x_i - x_i^n exactly.
#pragma once

#include <cmath>
#include <vector>

#include "potential/barrier.h"
#include "potential/node_term.h"
#include "potential/plane_barrier.h"
#include "potential/term.h"
#include "types.h"

namespace invfree {

constexpr double kFrictionEpsV = 1e-3;  // m/s, the demo's eps_v

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

// mu_f lambda for a node whose gap to the ground is `gap`: 0 beyond dhat.
inline double friction_weight(double mu_f, double gap, const BarrierParams& barrier) {
  return gap < barrier.dhat ? -mu_f * barrier_derivative(gap, barrier) : 0.0;
}

struct GroundFriction {
  static constexpr EnergyKind kind = EnergyKind::Friction;
  bool on = false;
  std::vector<double> weight;  // mu_f lambda_i per node, lagged
  double eps_u = 0.0;          // eps_v h
  bool sloped = false;
  Vec2 tangent = Vec2(1.0, 0.0);  // unit; read only when sloped
  double mu = 0.0;                // mu_f
  GroundBarrier ground;           // the normal force's barrier

  double slip(const NodeState& s) const {
    return sloped ? tangent.x() * (s.x - s.x_start) + tangent.y() * (s.y - s.y_start)
                  : s.x - s.x_start;
  }
  double value(const NodeState& s) const {
    const double w = weight[s.index];
    return w > 0.0 ? friction_value(slip(s), w, eps_u) : 0.0;
  }
  void add_derivatives(const NodeState& s, double scale, NodeDerivatives& d) const {
    const double w = weight[s.index];
    if (!(w > 0.0)) return;
    const double u = slip(s);
    const double d1 = scale * friction_derivative(u, w, eps_u);
    const double d2 = scale * friction_second_derivative(u, w, eps_u);
    if (!sloped) {
      d.gx += d1;
      d.hxx += d2;
      return;
    }
    add_along(d, tangent.x(), tangent.y(), d1, d2);
  }
  // Explicit integration: the force on the current slip h v, with the current normal force.
  void add_explicit_force(const NodeState& s, const Vec2& v, double h, NodeDerivatives& d) const {
    const double gap = ground.gap(s.x, s.y);
    if (!(gap < ground.barrier.dhat)) return;
    const double u = sloped ? h * tangent.dot(v) : h * v.x();
    const double f = friction_derivative(u, friction_weight(mu, gap, ground.at(s.index)), eps_u);
    d.gx += sloped ? f * tangent.x() : f;
    if (sloped) d.gy += f * tangent.y();
  }
};

}  // namespace invfree
