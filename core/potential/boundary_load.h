// The boundary loads of [traction] (scene/tractions.h), two terms of the potential, both of
// kind Load and scaled by the step's load factor (the ramp, scene.h's load_factor):
//  - DeadLoad, a node term: -factor f_i . (x_i - X_i) per node (f: the tables' forces spread
//    over their edges, X the rest positions). Linear in x: no Hessian.
//  - PressureLoad, a whole-mesh term: factor p A over whole boundary loops, A the loops'
//    signed area in the boundary's orientation, A = sum over edges a -> b of 1/2 x_a x x_b.
//    Its force on a node is p/2 times the normal of its two edges' chord, pointing into the
//    body: a follower load on the deformed edges. An edge's Hessian block is constant,
//    (p/2) [[0, J], [J^T, 0]] with J = [[0, 1], [-1, 0]], eigenvalues +-p/2; projected, only
//    its positive half is kept. On whole loops the sum is translation invariant.
#pragma once

#include <cmath>
#include <vector>

#include "potential/node_term.h"
#include "potential/term.h"
#include "scene/tractions.h"

namespace invfree {

struct DeadLoad {
  static constexpr EnergyKind kind = EnergyKind::Load;
  bool on = false;
  const double* force = nullptr;  // 2N
  // The rest positions: the work is measured from them, -f.(x - X), the same potential up
  // to a constant. From the origin, -f.x would add a constant as large as |f| times the
  // body's distance from the origin, and its rounding would drown the energy differences
  // of a small-strain static solve (Newton compares energies to 64 eps |E|).
  const Vec2* origin = nullptr;
  double factor = 1.0;

  double value(const NodeState& s) const {
    const Vec2& o = origin[s.index];
    return -factor * (force[2 * s.index] * (s.x - o.x()) + force[2 * s.index + 1] * (s.y - o.y()));
  }
  void add_derivatives(const NodeState& s, double scale, NodeDerivatives& d) const {
    d.gx -= scale * factor * force[2 * s.index];
    d.gy -= scale * factor * force[2 * s.index + 1];
  }
};

struct PressureLoad {
  static constexpr EnergyKind kind = EnergyKind::Load;
  static constexpr bool scaled_by_h2 = true;
  bool on = false;
  const std::vector<PressureEdge>* edges = nullptr;
  double factor = 1.0;
  bool project = true;  // keep only the PSD half of each edge's Hessian

  double value(const TermPoint& at, double scale) const {
    const double* z = at.z.data();
    double e = 0.0;
    for (const PressureEdge& edge : *edges) {
      const double cross = z[2 * edge.a] * z[2 * edge.b + 1] - z[2 * edge.b] * z[2 * edge.a + 1];
      e += 0.5 * edge.pressure * cross;
    }
    return scale * factor * e;
  }

  void add_gradient(const VecX& z, double scale, VecX& g) const {
    for (const PressureEdge& edge : *edges) {
      const double c = 0.5 * scale * factor * edge.pressure;
      g[2 * edge.a] += c * z[2 * edge.b + 1];
      g[2 * edge.a + 1] -= c * z[2 * edge.b];
      g[2 * edge.b] -= c * z[2 * edge.a + 1];
      g[2 * edge.b + 1] += c * z[2 * edge.a];
    }
  }

  void add_derivatives(const TermPoint& at, double scale, Assembly& out) const {
    add_gradient(at.z, scale, out.gradient);
    for (const PressureEdge& edge : *edges) {
      const double c = 0.5 * scale * factor * edge.pressure;
      // The 4x4 block over (x_a, y_a, x_b, y_b) is c M with M symmetric and M^2 = I
      // (eigenvalues +-1), so its PSD part is |c|/2 I + c/2 M: half the block plus |c|/2 on
      // the diagonal.
      Mat2 aa = Mat2::Zero(), ab;
      ab << 0.0, c, -c, 0.0;
      if (project) {
        aa = 0.5 * std::abs(c) * Mat2::Identity();
        ab *= 0.5;
      }
      const Mat2 ba = ab.transpose();
      add_node_block(out.hessian, edge.a, edge.a, aa);
      add_node_block(out.hessian, edge.b, edge.b, aa);
      add_node_block(out.hessian, edge.a, edge.b, ab);
      add_node_block(out.hessian, edge.b, edge.a, ba);
    }
  }

  void add_explicit_force(const TermPoint& at, VecX& gradient) const {
    add_gradient(at.z, 1.0, gradient);
  }
};

}  // namespace invfree
