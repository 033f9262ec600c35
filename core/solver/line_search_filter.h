// Line-search filters that bound the Newton step before backtracking (lecture 9,
// "Inversion-Free Line Search Filtering"; the demo's BarrierEnergy.init_step_size).
// Inputs: current positions x, search direction p (2N, plus the ceiling unknown last
// when `ceiling_on`). Outputs: the largest alpha in (0, 1] that keeps
//  - every triangle's signed area above 10% of its current value (the quadratic
//    a alpha^2 + b alpha + 0.9 = 0 in alpha, normalised by the current area), and
//  - every node at least 10% of its current gap away from the ground and ceiling.
#pragma once

#include "scene/mesh.h"

namespace invfree {

// Smallest strictly positive real root of a t^2 + b t + c = 0, or +infinity when there is
// none. Uses the cancellation-free form of the quadratic formula and treats a == 0 and
// b == 0 exactly (the coefficients are already dimensionless, so no tolerance is needed).
double smallest_positive_root(double a, double b, double c);

double inversion_free_step(const Mesh& mesh, const VecX& x, const VecX& p);

// The fraction of its current signed area below which the filter lets no triangle go
// (the 0.9 of the quadratic above is 1 - this), and that area itself (x: 2N positions).
constexpr double kMinAreaFraction = 0.1;
double signed_area(const VecX& x, const std::array<int, 3>& triangle);

struct PlaneFilter {
  bool ground_on = false;
  double ground_y = 0.0;
  bool ceiling_on = false;  // the ceiling height is x[2N], its direction p[2N]
};
double plane_step(const PlaneFilter& planes, int node_count, const VecX& x, const VecX& p);

}  // namespace invfree
