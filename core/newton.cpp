#include "core/newton.h"

#include <cmath>
#include <limits>

#include "core/line_search_filter.h"

namespace invfree {

namespace {
// The ceiling may jump to its target when that keeps every node at least 10% of its
// current gap away (the plane filter's rule); until then the penalty pulls it there.
bool ceiling_target_is_safe(const StepProblem& p, const VecX& z) {
  const int n = p.node_count();
  const double c = z[2 * n];
  for (int i = 0; i < n; ++i) {
    const double y = z[2 * i + 1];
    if (!(p.ceiling_target - y >= 0.1 * (c - y))) return false;
  }
  return true;
}
}  // namespace

NewtonResult minimize_incremental_potential(StepProblem& problem, const NewtonSettings& settings,
                                            NewtonWorkspace& ws, VecX& z) {
  NewtonResult result;
  const int n = problem.node_count();
  const PlaneFilter planes{problem.ground_on, problem.ground_y, problem.ceiling_on};
  const bool filter_inversions = settings.inversion_filter && !model_allows_inversion(problem.model);
  double energy = ip_energy(problem, z);
  for (result.iterations = 0; result.iterations < settings.max_iterations; ++result.iterations) {
    if (problem.ceiling_on && !problem.ceiling_fixed && ceiling_target_is_safe(problem, z)) {
      z[2 * n] = problem.ceiling_target;
      problem.ceiling_fixed = true;
      energy = ip_energy(problem, z);
    }
    ip_gradient_hessian(problem, z, ws.gradient, ws.hessian);
    if (!ws.solver.analyzed()) ws.solver.analyze(ws.hessian.matrix);
    if (!ws.solver.factorize(ws.hessian.matrix) || !ws.solver.solve(-ws.gradient, ws.direction)) {
      result.status = StepStatus::LinearSolveFailed;
      break;
    }
    result.residual = ws.direction.lpNorm<Eigen::Infinity>() / problem.h;
    if (result.residual < settings.tol) {
      if (!problem.ceiling_on || problem.ceiling_fixed) {
        result.energy = energy;
        return result;
      }
      problem.ceiling_stiffness *= 2.0;  // converged short of the ceiling's target
      energy = ip_energy(problem, z);
      continue;
    }

    double alpha = plane_step(planes, n, z, ws.direction);
    if (filter_inversions) alpha = std::min(alpha, inversion_free_step(*problem.mesh, z, ws.direction));
    // Near convergence the decrease a step can bring, -alpha g.p, falls below the
    // rounding noise of E itself (~1e-16 |E|); comparing energies is then meaningless and
    // backtracking would stall. There the filtered Newton step is taken as it is (the
    // quadratic model is exact to far better than the noise); the stopping test on
    // |p|_inf / h is unchanged.
    const double predicted_decrease = -alpha * ws.gradient.dot(ws.direction);
    const double energy_noise = 64.0 * std::numeric_limits<double>::epsilon() * (std::abs(energy) + 1.0);
    if (predicted_decrease >= 0.0 && predicted_decrease < energy_noise) {
      ws.trial = z + alpha * ws.direction;
      const double trial_energy = ip_energy(problem, ws.trial);
      if (std::isfinite(trial_energy)) {
        z.swap(ws.trial);
        energy = trial_energy;
        continue;
      }
    }
    int halvings = 0;
    double trial_energy;
    while (true) {
      ws.trial = z + alpha * ws.direction;
      trial_energy = ip_energy(problem, ws.trial);
      if (trial_energy <= energy || halvings == settings.max_halvings) break;
      alpha *= 0.5;
      ++halvings;
    }
    if (!(trial_energy <= energy)) {  // no descent along p: a failed Newton step
      result.status = StepStatus::NewtonFailed;
      break;
    }
    z.swap(ws.trial);
    energy = trial_energy;
  }
  if (result.status == StepStatus::Ok) result.status = StepStatus::NewtonFailed;
  result.energy = energy;
  return result;
}

}  // namespace invfree
