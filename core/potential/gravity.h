// Gravity's potential -m g.x per node (linear in x: no Hessian). With `weight` (the
// course's chapter 0 quirk, [gravity] per_spring: simulator2.py adds g inside its spring
// loop) node i weighs weight[i] times its mass: -w_i m g.x; nullptr: once per node.
#pragma once

#include "potential/node_term.h"
#include "potential/term.h"
#include "types.h"

namespace invfree {

struct Gravity {
  static constexpr EnergyKind kind = EnergyKind::Gravity;
  bool on = false;
  Vec2 g = Vec2::Zero();
  const double* weight = nullptr;  // per node; nullptr: 1

  double mass(const NodeState& s) const { return weight ? weight[s.index] * s.mass : s.mass; }
  double value(const NodeState& s) const { return -(mass(s) * (g.x() * s.x + g.y() * s.y)); }
  void add_derivatives(const NodeState& s, double scale, NodeDerivatives& d) const {
    const double m = mass(s);
    d.gx -= scale * m * g.x();
    d.gy -= scale * m * g.y();
  }
};

}  // namespace invfree
