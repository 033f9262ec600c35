// Contact with the two horizontal planes of the lecture's demo, per node: the ground
// y = y0 below the body (gap d = y_i - y0) and the ceiling above it at height c (gap
// d = c - y_i; c is an unknown of the step, see ceiling_penalty.h), each the log barrier
// b(d) of barrier.h. The plane filter bounds a step so that every node keeps at least 10%
// of its gap to each plane (the demo's BarrierEnergy.init_step_size), so the barrier never
// sees d <= 0 and every accepted state stays strictly between the planes.
// The ground may be sloped (the course's 4_friction): unit normal n, through (0, y0), gap
// d = n.(x_i - (0, y0)), gradient b' n, Hessian b'' n n^T. The horizontal ground keeps
// the plain arithmetic d = y_i - y0 (no products with n = (0, 1)).
// Both are node terms (term.h) of kind Contact; each plane's filter is its max_step.
#pragma once

#include <algorithm>

#include "potential/barrier.h"
#include "potential/node_term.h"
#include "potential/term.h"
#include "types.h"

namespace invfree {

// The barrier of node i: `b`, with the node's own contact area when the bodies of a scene
// differ in edge length (node_area, per node; nullptr: b.area for every node).
inline BarrierParams node_barrier(const BarrierParams& b, const double* node_area, int i) {
  if (!node_area) return b;
  BarrierParams own = b;
  own.area = node_area[i];
  return own;
}

struct GroundBarrier {
  static constexpr EnergyKind kind = EnergyKind::Contact;
  bool on = false;
  double y0 = 0.0;
  BarrierParams barrier;
  bool sloped = false;
  Vec2 normal = Vec2(0.0, 1.0);       // unit; read only when sloped
  const double* node_area = nullptr;  // see node_barrier

  double gap(double x, double y) const {
    return sloped ? normal.x() * x + normal.y() * (y - y0) : y - y0;
  }
  BarrierParams at(int i) const { return node_barrier(barrier, node_area, i); }
  double value(const NodeState& s) const { return barrier_value(gap(s.x, s.y), at(s.index)); }
  void add_derivatives(const NodeState& s, double scale, NodeDerivatives& d) const {
    const double g = gap(s.x, s.y);
    if (g >= barrier.dhat) return;
    const BarrierParams b = at(s.index);
    const double d1 = scale * barrier_derivative(g, b);
    const double d2 = scale * barrier_second_derivative(g, b);
    if (!sloped) {
      d.gy += d1;
      d.hyy += d2;
      return;
    }
    add_along(d, normal.x(), normal.y(), d1, d2);
  }
  // The largest step in [0, alpha] along p that keeps nodes [first, last) of the n at least
  // 10% of their gap (term_sums.h runs the nodes in blocks).
  double max_step(const VecX& x, int /*n*/, int first, int last, const VecX& p,
                  double alpha) const {
    for (int i = first; i < last; ++i) {
      const int y = 2 * i + 1;
      if (sloped) {
        const double closing = normal.x() * p[y - 1] + normal.y() * p[y];
        if (closing < 0.0) alpha = std::min(alpha, 0.9 * gap(x[y - 1], x[y]) / -closing);
      } else if (p[y] < 0.0) {
        alpha = std::min(alpha, 0.9 * (x[y] - y0) / -p[y]);
      }
    }
    return alpha;
  }
};

// b(c - y_i): d/dy_i = -b', d/dc = b', Hessian b'' [1 -1; -1 1] on (y_i, c).
struct CeilingBarrier {
  static constexpr EnergyKind kind = EnergyKind::Contact;
  bool on = false;
  BarrierParams barrier;
  const double* node_area = nullptr;  // see node_barrier

  BarrierParams at(int i) const { return node_barrier(barrier, node_area, i); }
  double value(const NodeState& s) const { return barrier_value(s.ceiling - s.y, at(s.index)); }
  void add_derivatives(const NodeState& s, double scale, NodeDerivatives& d) const {
    const double gap = s.ceiling - s.y;
    if (gap < barrier.dhat) {
      const BarrierParams b = at(s.index);
      const double d1 = scale * barrier_derivative(gap, b);
      const double d2 = scale * barrier_second_derivative(gap, b);
      d.gy -= d1;
      d.gc += d1;
      d.hyy += d2;
      d.hcc += d2;
      d.hyc -= d2;
    }
  }
  // The largest step in [0, alpha] along p that keeps nodes [first, last) of the n at least
  // 10% of their gap below the ceiling (p's last entry moves the ceiling).
  double max_step(const VecX& x, int n, int first, int last, const VecX& p, double alpha) const {
    const int c = 2 * n;
    for (int i = first; i < last; ++i) {
      const int y = 2 * i + 1;
      const double closing = p[c] - p[y];  // rate of change of the gap c - y_i
      if (closing < 0.0) alpha = std::min(alpha, 0.9 * (x[c] - x[y]) / -closing);
    }
    return alpha;
  }
  // The body's push on the ceiling at height c (N, >= 0): the sum of the barrier's forces
  // -b'(d) over the nodes closer than dhat below it. x: 2 per node (x, y).
  double push(const double* x, int nodes, double c) const {
    double total = 0.0;
    for (int i = 0; i < nodes; ++i) {
      const double d = c - x[2 * i + 1];
      if (d > 0.0 && d < barrier.dhat) total -= barrier_derivative(d, at(i));
    }
    return total;
  }
};

// Both planes' filters from alpha = 1 (tests).
inline double plane_step(const GroundBarrier& ground, const CeilingBarrier& ceiling, int nodes,
                         const VecX& x, const VecX& p) {
  double alpha = 1.0;
  if (ground.on) alpha = ground.max_step(x, nodes, 0, nodes, p, alpha);
  if (ceiling.on) alpha = ceiling.max_step(x, nodes, 0, nodes, p, alpha);
  return alpha;
}

}  // namespace invfree
