// The live window's grab: a spring k/2 |x_node - target|^2 pulling one node toward the
// mouse while the user drags it. Off in every scene.
#pragma once

#include "types.h"

namespace invfree {

struct PullSpring {
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
};

}  // namespace invfree
