// The IPC log barrier on a distance d (Li et al. 2020, "Incremental Potential Contact",
// eq. 6), scaled as in the lecture's demo by the contact area a per node and by dhat:
//   b(d) = a dhat kappa/2 (s - 1) ln s,  s = d / dhat, for 0 < d < dhat; 0 beyond,
//   b'(d) = a kappa/2 (ln s + 1 - 1/s) <= 0,   b''(d) = a kappa/(2 dhat) (1/s + 1/s^2) > 0.
// The scaling keeps kappa a stiffness per unit length of boundary, so the force of a
// resting body on a plane does not depend on the mesh size. Every contact term (the ground
// and ceiling planes, core/potential/plane_barrier.h) uses this b.
#pragma once

#include <cmath>
#include <limits>

namespace invfree {

struct BarrierParams {
  double dhat = 0.01;
  double kappa = 1e5;
  double area = 0.25;  // contact area per node
};

// +infinity at or below d = 0: the feasible set's boundary.
inline double barrier_value(double d, const BarrierParams& b) {
  if (!(d > 0.0)) return std::numeric_limits<double>::infinity();
  if (d >= b.dhat) return 0.0;
  const double s = d / b.dhat;
  return b.area * b.dhat * 0.5 * b.kappa * (s - 1.0) * std::log(s);
}

inline double barrier_derivative(double d, const BarrierParams& b) {
  if (d >= b.dhat) return 0.0;
  const double s = d / b.dhat;
  return b.area * 0.5 * b.kappa * (std::log(s) + 1.0 - 1.0 / s);
}

inline double barrier_second_derivative(double d, const BarrierParams& b) {
  if (d >= b.dhat) return 0.0;
  const double s = d / b.dhat;
  return b.area * 0.5 * b.kappa / b.dhat * (1.0 / s + 1.0 / (s * s));
}

}  // namespace invfree
