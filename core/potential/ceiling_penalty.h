// The moving ceiling as an unknown c of the step (the demo's moving Dirichlet boundary):
// a penalty 1/2 k (c - c_target)^2 pulls it to its prescribed height. Newton stiffens k
// until c is within tol h of the target, or sets c exactly there ("fixed") as soon as
// that keeps every node at least 10% of its gap below it (core/solver/newton.cpp). The
// stiffness a step ends with is kept in the simulation's state for the next one.
#pragma once

#include "types.h"

namespace invfree {

struct CeilingPenalty {
  double target = 0.0;
  double stiffness = 0.0;  // k, already multiplied by the ceiling's mass
  bool fixed = false;      // c is at its target and no longer an unknown

  double value(double c) const {
    const double gap = c - target;
    return 0.5 * stiffness * gap * gap;
  }
  double gradient(double c) const { return stiffness * (c - target); }
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
