// The live window's grab: a spring k/2 |x_node - target|^2 pulling one node toward the
// mouse while the user drags it. Off in every scene. A whole-mesh term (term.h) of kind
// Control: input, not part of the body's mechanical energy.
#pragma once

#include "potential/term.h"
#include "types.h"

namespace invfree {

struct PullSpring {
  static constexpr EnergyKind kind = EnergyKind::Control;
  static constexpr bool scaled_by_h2 = true;
  bool on = false;
  int node = 0;
  Vec2 target = Vec2::Zero();
  double stiffness = 0.0;  // N/m

  // scale * k/2 |x - target|^2
  double value(const Vec2& x, double scale) const {
    return 0.5 * scale * stiffness * (x - target).squaredNorm();
  }
  // scale * k (x - target) added to the node's gradient (gx, gy); scale * k to its Hessian
  // diagonal.
  void add_derivatives(const Vec2& x, double scale, double& gx, double& gy, double& hxx,
                       double& hyy) const {
    const double k = scale * stiffness;
    gx += k * (x.x() - target.x());
    gy += k * (x.y() - target.y());
    hxx += k;
    hyy += k;
  }

  double value(const TermPoint& at, double scale) const {
    return value(at.z.segment<2>(2 * node), scale);
  }
  void add_derivatives(const TermPoint& at, double scale, Assembly& out) const {
    const int ix = 2 * node, iy = ix + 1;
    double* values = out.hessian.values();
    add_derivatives(at.z.segment<2>(ix), scale, out.gradient[ix], out.gradient[iy],
                    values[out.hessian.diagonal_slots[ix]], values[out.hessian.diagonal_slots[iy]]);
  }
  void add_explicit_force(const TermPoint& at, VecX& gradient) const {
    double hxx = 0.0, hyy = 0.0;
    add_derivatives(at.z.segment<2>(2 * node), 1.0, gradient[2 * node], gradient[2 * node + 1],
                    hxx, hyy);
  }
};

}  // namespace invfree
