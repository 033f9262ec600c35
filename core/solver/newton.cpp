#include "solver/newton.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "solver/self_contact_filter.h"

namespace invfree {

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kMaxExpansions = 4;  // alpha up to 16

double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// One minimisation: the problem, its settings and workspace, and the report it fills.
struct Newton {
  StepProblem& p;
  const NewtonSettings& settings;
  NewtonWorkspace& ws;
  NewtonResult& result;

  double energy(const VecX& at) {
    const auto t = Clock::now();
    const double e = ip_energy(p, at);
    result.line_search_ms += ms_since(t);
    ++result.energy_evaluations;
    return e;
  }

  // largest_feasible_step and, with self-contact, the CCD (which rebuilds the candidates
  // for the segment z -> z + alpha dir).
  double feasible_step(const VecX& z, const VecX& dir) {
    double alpha = largest_feasible_step(p, z, dir);
    if (p.self_contact.on && alpha > 0.0)
      alpha = self_contact_filter(p.self_contact, z, dir, alpha, ws.contact_grid);
    return alpha;
  }

  // z moved toward x^n + h v^n as far as the filters allow (the ceiling stays).
  void warm_start(VecX& z) {
    const auto t = Clock::now();
    const int n = p.node_count();
    ws.direction.head(2 * n) = p.x_tilde - z.head(2 * n);
    if (p.ceiling.on) ws.direction[2 * n] = 0.0;
    const double alpha = feasible_step(z, ws.direction);
    if (alpha > 0.0) z.head(2 * n) += alpha * ws.direction.head(2 * n);
    result.line_search_ms += ms_since(t);
  }

  // Sets the ceiling exactly at its target once that is safe; returns whether it moved.
  bool fix_ceiling_when_safe(VecX& z) {
    if (!p.ceiling.on || p.ceiling_penalty.fixed ||
        !ceiling_target_is_safe(p.ceiling_penalty, p.node_count(), z))
      return false;
    z[2 * p.node_count()] = p.ceiling_penalty.target;
    p.ceiling_penalty.fixed = true;
    return true;
  }

  // The ceiling counts as at its target once within tol h of it (the demo's DBC test).
  bool ceiling_at_target(const VecX& z) const {
    return !p.ceiling.on || p.ceiling_penalty.fixed ||
           std::abs(z[2 * p.node_count()] - p.ceiling_penalty.target) < settings.tol * p.h;
  }

  // p = -H^-1 g at z into ws.direction (ws.gradient, ws.hessian hold g and H).
  bool newton_direction(const VecX& z) {
    const auto t = Clock::now();
    ip_gradient_hessian(p, z, ws.gradient, ws.hessian);
    ws.rhs = -ws.gradient;
    result.assembly_ms += ms_since(t);
    if (ws.hessian.pattern_version != ws.analyzed_pattern) {  // contact blocks changed it
      ws.solver.setup(ws.hessian.matrix, ws.solver.requested(), ws.solver.positive_definite());
      ws.analyzed_pattern = ws.hessian.pattern_version;
    }
    SolveRequest request;
    request.threshold = settings.tol * p.h;
    if (p.elasticity.projection != HessianProjection::None) {
      // Every eigenvalue of the projected Hessian is at least the smallest node mass, the
      // ceiling's penalty stiffness, or 1 for the eliminated ceiling or fixed nodes
      // (linear_solver.h).
      double lambda = ws.min_node_mass;
      if (p.ceiling.on)
        lambda = std::min(lambda, p.ceiling_penalty.fixed ? 1.0 : p.ceiling_penalty.stiffness);
      if (p.fixed.on) lambda = std::min(lambda, 1.0);  // the fixed nodes' identity rows
      request.lambda_min = lambda;
      request.forcing = settings.forcing;
    } else {
      request.lambda_min = 0.0;
      request.forcing = 1e-13;  // no error bound: as exact as a direct solve
    }
    return ws.solver.solve(ws.hessian.matrix, ws.rhs, ws.direction, request, result.linear);
  }

  // Backtracking from the filtered step: the trial z + alpha p (friction crossings stopped)
  // whose energy does not exceed `current`, in ws.trial. Returns its energy, or NaN when no
  // halving descends. `halvings` and `stopped` report how it got there.
  double backtrack(const VecX& z, double alpha, double current, int& halvings, int& stopped) {
    const bool stop_crossings = settings.friction_crossing_stop && p.friction.on;
    halvings = stopped = 0;
    double trial_energy;
    while (true) {
      ws.trial = z + alpha * ws.direction;
      if (stop_crossings) stopped = stop_friction_crossings(p, z, ws.trial, ws.crossings);
      if (stopped > 0 && p.self_contact.on &&
          self_contact_path_step(p.self_contact, z, ws.trial, ws.contact_scratch) < 1.0) {
        ws.trial = z + alpha * ws.direction;  // the stops would cross an edge: the straight trial
        stopped = 0;
      }
      trial_energy = energy(ws.trial);
      if (trial_energy <= current || halvings == settings.max_halvings) break;
      alpha *= 0.5;
      ++halvings;
    }
    return trial_energy <= current ? trial_energy : std::numeric_limits<double>::quiet_NaN();
  }

  // Step expansion (newton.h): the full step was taken and E fell at least 1.5 times what
  // the quadratic model predicts, so the minimiser along p lies beyond alpha = 2. Doubles
  // alpha while E keeps falling and the filters allow; ws.trial and the returned energy
  // are the best point found.
  double expand(const VecX& z, double trial_energy, double current) {
    ws.trial2.noalias() = ws.hessian.matrix * ws.direction;
    const double model_decrease =
        -(ws.gradient.dot(ws.direction) + 0.5 * ws.direction.dot(ws.trial2));
    if (!(model_decrease > 0.0 && current - trial_energy > 1.5 * model_decrease))
      return trial_energy;
    double step = 1.0;
    // With self-contact, one filter call for the longest expansion (see newton.h).
    double contact_limit = 0.0;
    if (p.self_contact.on) {
      const double longest = double(1 << kMaxExpansions);
      ws.trial2 = longest * ws.direction;
      contact_limit = longest * feasible_step(z, ws.trial2);
    }
    for (int k = 0; k < kMaxExpansions; ++k) {
      const double next = 2.0 * step;
      if (p.self_contact.on && next > contact_limit) break;
      ws.trial2 = next * ws.direction;
      if (largest_feasible_step(p, z, ws.trial2) < 1.0) break;
      ws.trial2 += z;
      const double e2 = energy(ws.trial2);
      if (!(e2 < trial_energy)) break;
      ws.trial.swap(ws.trial2);
      trial_energy = e2;
      step = next;
    }
    if (step > 1.0) ++result.expanded_steps;
    return trial_energy;
  }
};

}  // namespace

NewtonResult minimize_incremental_potential(StepProblem& problem, const NewtonSettings& settings,
                                            NewtonWorkspace& ws, VecX& z) {
  NewtonResult result;
  Newton newton{problem, settings, ws, result};
  const int dofs = problem.dof_count();
  for (VecX* v : {&ws.direction, &ws.rhs, &ws.trial, &ws.trial2})
    if (v->size() != dofs) v->resize(dofs);

  if (settings.predictor) newton.warm_start(z);
  if (problem.self_contact.on) self_contact_candidates_at(problem.self_contact, z, ws.contact_grid);
  double energy = newton.energy(z);
  for (result.iterations = 0; result.iterations < settings.max_iterations; ++result.iterations) {
    if (newton.fix_ceiling_when_safe(z)) energy = newton.energy(z);
    if (!newton.newton_direction(z)) {
      result.status = StepStatus::LinearSolveFailed;
      break;
    }
    // Stop when |p|_inf / h < tol, but never before one step: where the whole step's
    // motion is below tol h (a square at rest with h g < tol) the start would be accepted
    // every step and the square would never start to fall.
    result.residual = ws.direction.lpNorm<Eigen::Infinity>() / problem.h;
    if (result.residual < settings.tol && result.iterations > 0) {
      if (newton.ceiling_at_target(z)) {
        result.energy = energy;
        return result;
      }
      problem.ceiling_penalty.stiffness *= 2.0;  // converged short of the ceiling's target
      ++result.penalty_doublings;
      energy = newton.energy(z);
      continue;
    }

    const auto t = Clock::now();
    const double alpha = newton.feasible_step(z, ws.direction);
    result.line_search_ms += ms_since(t);
    // Near convergence the decrease a step can bring, -alpha g.p, falls below the rounding
    // noise of E itself (~1e-16 |E|): comparing energies is meaningless there and
    // backtracking would stall, so the filtered step is taken as it is (the stopping test
    // is unchanged).
    const double predicted_decrease = -alpha * ws.gradient.dot(ws.direction);
    const double energy_noise =
        64.0 * std::numeric_limits<double>::epsilon() * (std::abs(energy) + 1.0);
    if (predicted_decrease >= 0.0 && predicted_decrease < energy_noise) {
      ws.trial = z + alpha * ws.direction;
      const double trial_energy = newton.energy(ws.trial);
      if (std::isfinite(trial_energy)) {
        z.swap(ws.trial);
        energy = trial_energy;
        continue;
      }
    }
    int halvings, stopped;
    double trial_energy = newton.backtrack(z, alpha, energy, halvings, stopped);
    if (std::isnan(trial_energy)) {  // no descent along p: a failed Newton step
      result.status = StepStatus::NewtonFailed;
      break;
    }
    result.stopped_nodes += stopped;
    // Not after a crossing stop: the trial is then off the line z + alpha p.
    if (settings.step_expansion && halvings == 0 && alpha == 1.0 && stopped == 0)
      trial_energy = newton.expand(z, trial_energy, energy);
    z.swap(ws.trial);
    energy = trial_energy;
  }
  if (result.status == StepStatus::Ok) result.status = StepStatus::NewtonFailed;
  result.energy = energy;
  return result;
}

}  // namespace invfree
