// The moving ceiling as an unknown c of the step (the demo's moving Dirichlet boundary):
// a penalty 1/2 k (c - c_target)^2 pulls it to its prescribed height. Newton stiffens k
// until c is within tol h of the target, or sets c exactly there ("fixed") as soon as
// that keeps every node at least 10% of its gap below it (core/solver/newton.cpp). The
// stiffness a step ends with is kept in the simulation's state for the next one.
// A control term (term.h): not scaled by h^2, and it steers Newton's stopping test
// (settle, at_target, tighten).
#pragma once

#include <cmath>

#include "potential/term.h"
#include "types.h"

namespace invfree {

struct CeilingPenalty;
inline bool ceiling_target_is_safe(const CeilingPenalty& penalty, int node_count, const VecX& z);

struct CeilingPenalty {
  static constexpr EnergyKind kind = EnergyKind::Control;
  static constexpr bool scaled_by_h2 = false;
  bool on = false;
  double target = 0.0;
  double stiffness = 0.0;  // k, already multiplied by the ceiling's mass
  bool fixed = false;      // c is at its target and no longer an unknown

  double value(double c) const { return value_at(c, 1.0); }
  double gradient(double c) const { return stiffness * (c - target); }

  double value(const TermPoint& at, double scale) const {
    return value_at(at.z[2 * at.node_count()], scale);
  }
  // The ceiling's own entries; the nodes' barrier terms added theirs before. A fixed
  // ceiling is eliminated from the system (its row and column those of the identity): the
  // node pass left its couplings at zero (term_sums.h), so only the diagonal is set.
  void add_derivatives(const TermPoint& at, double, Assembly& out) const {
    const int c = 2 * at.node_count();
    out.gradient[c] += gradient(at.z[c]);
    out.hessian.values()[out.hessian.diagonal_slots[c]] += stiffness;
    if (fixed) {
      out.gradient[c] = 0.0;
      out.hessian.values()[out.hessian.diagonal_slots[c]] = 1.0;
    }
  }

  // Sets the ceiling exactly at its target once that is safe; returns whether z changed.
  bool settle(int nodes, VecX& z) {
    if (fixed || !ceiling_target_is_safe(*this, nodes, z)) return false;
    z[2 * nodes] = target;
    fixed = true;
    return true;
  }
  // At its target once within `tolerance` of it (the demo's DBC test, tol h).
  bool at_target(int nodes, const VecX& z, double tolerance) const {
    return fixed || std::abs(z[2 * nodes] - target) < tolerance;
  }
  // Converged short of the target: a stiffer pull (the demo doubles k).
  void tighten() { stiffness *= 2.0; }
  // The smallest eigenvalue this term gives the ceiling's row (linalg/pcg.h's bound).
  double hessian_floor() const { return fixed ? 1.0 : stiffness; }

 private:
  double value_at(double c, double scale) const {
    const double gap = c - target;
    return 0.5 * scale * stiffness * gap * gap;
  }
};

// True when moving the ceiling from z[2n] to the target keeps every node at least 10% of
// its current gap below it (the plane filter's rule).
inline bool ceiling_target_is_safe(const CeilingPenalty& penalty, int node_count, const VecX& z) {
  const double c = z[2 * node_count];
  for (int i = 0; i < node_count; ++i) {
    const double y = z[2 * i + 1];
    if (!(penalty.target - y >= 0.1 * (c - y))) return false;
  }
  return true;
}

}  // namespace invfree
