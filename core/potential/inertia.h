// Inertia of implicit Euler: 1/2 |x - x_tilde|^2_M with x_tilde = x^n + h v^n and the
// lumped (diagonal) mass matrix M; the incremental potential's only term not scaled by h^2.
// Per node: value 1/2 m |x_i - x_tilde_i|^2, gradient m (x_i - x_tilde_i), Hessian m I.
#pragma once

#include "potential/node_term.h"

namespace invfree {

inline double inertia_value(const NodeState& s, double x_tilde, double y_tilde) {
  const double dx = s.x - x_tilde, dy = s.y - y_tilde;
  return 0.5 * s.mass * (dx * dx + dy * dy);
}

// Sets (does not add) the node's derivatives: inertia is the first term of every sum.
inline void set_inertia_derivatives(const NodeState& s, double x_tilde, double y_tilde,
                                    NodeDerivatives& d) {
  d = NodeDerivatives{};
  d.gx = s.mass * (s.x - x_tilde);
  d.gy = s.mass * (s.y - y_tilde);
  d.hxx = s.mass;
  d.hyy = s.mass;
}

}  // namespace invfree
