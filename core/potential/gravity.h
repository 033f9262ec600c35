// Gravity's potential -m g.x per node (linear in x: no Hessian).
#pragma once

#include "potential/node_term.h"
#include "potential/term.h"
#include "types.h"

namespace invfree {

struct Gravity {
  static constexpr EnergyKind kind = EnergyKind::Gravity;
  bool on = false;
  Vec2 g = Vec2::Zero();

  double value(const NodeState& s) const { return -(s.mass * (g.x() * s.x + g.y() * s.y)); }
  void add_derivatives(const NodeState& s, double scale, NodeDerivatives& d) const {
    d.gx -= scale * s.mass * g.x();
    d.gy -= scale * s.mass * g.y();
  }
};

}  // namespace invfree
