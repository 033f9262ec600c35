// Contact with the two horizontal planes of the lecture's demo, per node: the ground
// y = y0 below the body (gap d = y_i - y0) and the ceiling above it at height c (gap
// d = c - y_i; c is an unknown of the step, see ceiling_penalty.h), each the log barrier
// b(d) of barrier.h. The plane filter bounds a step so that every node keeps at least 10%
// of its gap to each plane (the demo's BarrierEnergy.init_step_size), so the barrier never
// sees d <= 0 and every accepted state stays strictly between the planes.
#pragma once

#include <algorithm>

#include "potential/barrier.h"
#include "potential/node_term.h"
#include "types.h"

namespace invfree {

struct GroundBarrier {
  bool on = false;
  double y0 = 0.0;
  BarrierParams barrier;

  double value(const NodeState& s) const { return barrier_value(s.y - y0, barrier); }
  void add_derivatives(const NodeState& s, double scale, NodeDerivatives& d) const {
    const double gap = s.y - y0;
    if (gap < barrier.dhat) {
      d.gy += scale * barrier_derivative(gap, barrier);
      d.hyy += scale * barrier_second_derivative(gap, barrier);
    }
  }
};

// b(c - y_i): d/dy_i = -b', d/dc = b', Hessian b'' [1 -1; -1 1] on (y_i, c).
struct CeilingBarrier {
  bool on = false;
  BarrierParams barrier;

  double value(const NodeState& s) const { return barrier_value(s.ceiling - s.y, barrier); }
  void add_derivatives(const NodeState& s, double scale, NodeDerivatives& d) const {
    const double gap = s.ceiling - s.y;
    if (gap < barrier.dhat) {
      const double d1 = scale * barrier_derivative(gap, barrier);
      const double d2 = scale * barrier_second_derivative(gap, barrier);
      d.gy -= d1;
      d.gc += d1;
      d.hyy += d2;
      d.hcc += d2;
      d.hyc -= d2;
    }
  }
};

// The largest alpha in (0, 1] that keeps every node at least 10% of its current gap from
// each plane that is on, along direction p (2 per node, then the ceiling's own entry).
inline double plane_step(const GroundBarrier& ground, const CeilingBarrier& ceiling, int node_count,
                         const VecX& x, const VecX& p) {
  double alpha = 1.0;
  const int c = 2 * node_count;
  for (int i = 0; i < node_count; ++i) {
    const int y = 2 * i + 1;
    if (ground.on && p[y] < 0.0) alpha = std::min(alpha, 0.9 * (x[y] - ground.y0) / -p[y]);
    if (ceiling.on) {
      const double closing = p[c] - p[y];  // rate of change of the gap c - y_i
      if (closing < 0.0) alpha = std::min(alpha, 0.9 * (x[c] - x[y]) / -closing);
    }
  }
  return alpha;
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

}  // namespace invfree
