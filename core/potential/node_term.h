// What a per-node term of the incremental potential sees and produces. A node term
// (gravity.h, plane_barrier.h, friction.h) is a struct with
//   bool on;                                               // switched on by the scene
//   double value(const NodeState&) const;                  // its energy at this node
//   void add_derivatives(const NodeState&, double scale,   // scale * its gradient and
//                        NodeDerivatives&) const;          // projected Hessian, added
// The sum over terms (incremental_potential.cpp) and explicit integration
// (simulation.cpp) call these in the order the terms are listed there.
#pragma once

namespace invfree {

struct NodeState {
  int index = 0;
  double x = 0.0, y = 0.0;  // the node's position
  double mass = 0.0;
  double x_start = 0.0;  // x at the step's start (lagged friction's reference)
  double ceiling = 0.0;  // the ceiling's height, an unknown of the step when it has one
  double y_start = 0.0;  // y at the step's start (friction on a sloped ground)
};

// Gradient and Hessian entries of one node: with respect to (x_i, y_i), and the coupling
// of y_i to the ceiling unknown c (its gradient, its diagonal, the (y_i, c) entry), and
// the (x_i, y_i) entry (nonzero only for a sloped ground).
struct NodeDerivatives {
  double gx = 0.0, gy = 0.0, hxx = 0.0, hyy = 0.0;
  double gc = 0.0, hcc = 0.0, hyc = 0.0;
  double hxy = 0.0;
};

// Adds a term f(u.x) whose variable is the node's position along the unit direction u (a
// sloped ground's normal or tangent): gradient f' u, Hessian f'' u u^T (d1 = f', d2 = f'').
inline void add_along(NodeDerivatives& d, double ux, double uy, double d1, double d2) {
  d.gx += d1 * ux;
  d.gy += d1 * uy;
  d.hxx += d2 * ux * ux;
  d.hyy += d2 * uy * uy;
  d.hxy += d2 * ux * uy;
}

}  // namespace invfree
