#include "solver/friction_crossing.h"

#include <cmath>

namespace invfree {

int stop_friction_crossings(const StepProblem& problem, const VecX& z, VecX& trial,
                            FrictionCrossingScratch& s) {
  if (!problem.friction.on || problem.friction.sloped) return 0;  // stops along x only
  const int n = problem.node_count();
  if (static_cast<int>(s.stopped.size()) != n) {
    s.stopped.assign(n, 0);
    s.nodes.reserve(n);
    s.step_x.resize(n);
  }
  s.nodes.clear();
  for (int i = 0; i < n; ++i) {
    if (problem.friction.weight[i] <= 0.0) continue;
    const double x0 = problem.x_start[2 * i];
    const double u0 = z[2 * i] - x0, u1 = trial[2 * i] - x0;
    if (u0 * u1 < 0.0 && std::abs(u1) >= problem.friction.eps_u) {
      s.stopped[i] = 1;
      s.step_x[i] = trial[2 * i];
      trial[2 * i] = x0;
      s.nodes.push_back(i);
    }
  }
  if (s.nodes.empty()) return 0;
  // Give the step's x back to the stopped nodes of every triangle the stops squeezed
  // below 10% of its area, until none is (with every node back, trial is the straight
  // point, which the inversion filter already cleared).
  for (bool restored = true; restored;) {
    restored = false;
    for (const auto& t : problem.mesh->triangles) {
      if (!(s.stopped[t[0]] || s.stopped[t[1]] || s.stopped[t[2]])) continue;
      if (signed_area(trial, t) >= kMinAreaFraction * signed_area(z, t)) continue;
      for (int v : t)
        if (s.stopped[v]) {
          s.stopped[v] = 0;
          trial[2 * v] = s.step_x[v];
          restored = true;
        }
    }
  }
  int count = 0;
  for (int i : s.nodes) {
    count += s.stopped[i];
    s.stopped[i] = 0;  // leave the flags clear for the next call
  }
  return count;
}

}  // namespace invfree
