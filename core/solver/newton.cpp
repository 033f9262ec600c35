#include "solver/newton.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "linalg/blocked_vector_ops.h"
#include "solver/newton_interrupt.h"

namespace invfree {

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kMaxExpansions = 4;  // alpha up to 16

double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// One minimisation: the problem, its caches, settings and workspace, and the report.
struct Newton {
  StepProblem& p;
  StepCaches& caches;
  const NewtonSettings& settings;
  NewtonWorkspace& ws;
  NewtonResult& result;

  double energy(const VecX& at) {
    const auto t = Clock::now();
    const double e = ip_energy(p, caches, at);
    result.line_search_ms += ms_since(t);
    ++result.energy_evaluations;
    return e;
  }

  // Every term's filter (a stateful one, self-contact's, gathers its candidates for the
  // segment z -> z + alpha dir).
  double feasible_step(const VecX& z, const VecX& dir) {
    return largest_safe_step(p, caches, z, dir);
  }

  // z moved toward x^n + h v^n as far as the filters allow (the ceiling stays).
  void warm_start(VecX& z) {
    const auto t = Clock::now();
    const int n = p.node_count();
    ws.direction.head(2 * n) = p.x_tilde - z.head(2 * n);
    if (p.dof_count() > 2 * n) ws.direction[2 * n] = 0.0;
    const double alpha = feasible_step(z, ws.direction);
    if (alpha > 0.0) z.head(2 * n) += alpha * ws.direction.head(2 * n);
    result.line_search_ms += ms_since(t);
  }

  // p = -H^-1 g at z into ws.direction (ws.gradient, ws.hessian hold g and H).
  bool newton_direction(const VecX& z) {
    // Where PCG solves a projected (positive definite) Hessian, contact blocks outside the
    // pattern stay couplings: no rebuild, no new analysis.
    ws.hessian.keep_couplings = !ws.reduced.on() && settings.projected &&
                                solves_by_pcg(settings.linear_solver, settings.projected);
    if (full_space_direction(z)) return true;
    if (ws.hessian.couplings.empty()) return false;
    // PCG failed on a fresh factor too (never seen): the couplings join the pattern (a
    // rebuild and a new analysis) and the factor holds them.
    ws.hessian.keep_couplings = false;
    return full_space_direction(z);
  }

  bool full_space_direction(const VecX& z) {
    const auto t = Clock::now();
    ip_gradient_hessian(p, caches, z, ws.gradient, ws.hessian);
    blocked_negate(ws.gradient, ws.rhs);
    result.assembly_ms += ms_since(t);
    if (ws.reduced.on()) return reduced_direction();
    prepare_linear_solver(ws, settings.linear_solver, settings.projected);
    SolveRequest request;
    request.couplings = ws.hessian.couplings;
    request.threshold = settings.tol * p.h;
    if (settings.projected) {
      request.lambda_min = hessian_lower_bound(p, ws.min_node_mass);
      request.forcing = settings.forcing;
    } else {
      request.lambda_min = 0.0;
      request.forcing = 1e-13;  // no error bound: as exact as a direct solve
    }
    return ws.solver.solve(ws.hessian.matrix, ws.rhs, ws.direction, request, result.linear);
  }

  // The subspace's step: B^T H B and -B^T g (counted as assembly), their dense LDL^T
  // (factorisation), q and p = B q (solve).
  bool reduced_direction() {
    ReducedSolve& r = ws.reduced;
    auto t = Clock::now();
    if (r.transposed.cols() != r.basis.rows()) r.transposed = r.basis.transpose();
    r.transposed_times_hessian.noalias() = r.transposed * ws.hessian.matrix;
    r.hessian.noalias() = r.transposed_times_hessian * r.basis;
    r.rhs.noalias() = r.transposed * ws.rhs;
    result.assembly_ms += ms_since(t);
    t = Clock::now();
    r.factor.compute(r.hessian);
    result.linear.factor_ms += ms_since(t);
    ++result.linear.factorizations;
    if (r.factor.info() != Eigen::Success) return false;
    t = Clock::now();
    r.step = r.factor.solve(r.rhs);
    ws.direction.noalias() = r.basis * r.step;
    result.linear.solve_ms += ms_since(t);
    ++result.linear.solves;
    return ws.direction.allFinite();
  }

  // Backtracking from the filtered step: the trial z + alpha p (friction crossings stopped)
  // whose energy does not exceed `current`, in ws.trial. Returns its energy, or NaN when no
  // halving descends. `halvings` and `stopped` report how it got there.
  double backtrack(const VecX& z, double alpha, double current, int& halvings, int& stopped) {
    halvings = stopped = 0;
    double trial_energy;
    while (true) {
      blocked_add_scaled(z, alpha, ws.direction, ws.trial);
      if (settings.friction_crossing_stop)
        stopped = stop_friction_crossings(p, z, ws.trial, ws.crossings);
      if (stopped > 0 && path_step(p, caches, z, ws.trial) < 1.0) {
        // The stops would cross an edge: the straight trial.
        blocked_add_scaled(z, alpha, ws.direction, ws.trial);
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
  // are the best point found. One filter call covers the longest expansion (see newton.h);
  // the length is a power of two, so the filters' steps scale exactly and this limit
  // decides each doubling as a filter call of its own would.
  double expand(const VecX& z, double trial_energy, double current) {
    multiply_hessian(ws.hessian, ws.direction, ws.trial2);
    const double model_decrease =
        -(ws.gradient.dot(ws.direction) + 0.5 * ws.direction.dot(ws.trial2));
    if (!(model_decrease > 0.0 && current - trial_energy > 1.5 * model_decrease))
      return trial_energy;
    double step = 1.0;
    const double longest = double(1 << kMaxExpansions);
    ws.trial2 = longest * ws.direction;
    const double limit = longest * feasible_step(z, ws.trial2);
    for (int k = 0; k < kMaxExpansions; ++k) {
      const double next = 2.0 * step;
      if (next > limit) break;
      blocked_add_scaled(z, next, ws.direction, ws.trial2);
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

namespace {
NewtonInterruptCheck g_interrupt_check = nullptr;
}  // namespace

void set_newton_interrupt_check(NewtonInterruptCheck check) {
  g_interrupt_check = check;
}

void prepare_linear_solver(NewtonWorkspace& ws, LinearSolverKind kind, bool projected) {
  LinearSolver& solver = ws.solver;
  if (solver.ready() && solver.requested() == kind && solver.positive_definite() == projected &&
      ws.analyzed_pattern == ws.hessian.pattern_version)
    return;
  solver.setup(ws.hessian.matrix, kind, projected);
  ws.analyzed_pattern = ws.hessian.pattern_version;
  ++ws.analyses;
}

NewtonResult minimize_incremental_potential(StepProblem& problem, StepCaches& caches,
                                            const NewtonSettings& settings, NewtonWorkspace& ws,
                                            VecX& z) {
  NewtonResult result;
  Newton newton{problem, caches, settings, ws, result};
  const int dofs = problem.dof_count();
  for (VecX* v : {&ws.direction, &ws.rhs, &ws.trial, &ws.trial2})
    if (v->size() != dofs) v->resize(dofs);

  if (settings.predictor) newton.warm_start(z);
  begin_terms(problem, caches, z);
  double energy = newton.energy(z);
  for (result.iterations = 0; result.iterations < settings.max_iterations; ++result.iterations) {
    if (g_interrupt_check != nullptr && result.iterations > 0 && g_interrupt_check()) {
      result.status = StepStatus::NewtonFailed;  // asked to stop (newton_interrupt.h)
      result.energy = energy;
      return result;
    }
    if (settle_controls(problem, z)) energy = newton.energy(z);
    if (!newton.newton_direction(z)) {
      result.status = StepStatus::LinearSolveFailed;
      break;
    }
    // Stop when |p|_inf / h < tol, but never before one step: where the whole step's
    // motion is below tol h (a square at rest with h g < tol) the start would be accepted
    // every step and the square would never start to fall.
    result.residual = blocked_max_abs(ws.direction) / problem.h;
    if (result.residual < settings.tol && result.iterations > 0) {
      if (controls_at_target(problem, z, settings.tol * problem.h)) {
        result.energy = energy;
        return result;
      }
      tighten_controls(problem);  // converged short of a control's target
      ++result.penalty_doublings;
      energy = newton.energy(z);
      continue;
    }

    const auto t = Clock::now();
    const double alpha = newton.feasible_step(z, ws.direction);
    result.line_search_ms += ms_since(t);
    // Near convergence the decrease a step can bring, -alpha g.p, falls below the rounding
    // noise of E itself (~1e-16 |E|, and in a static step the cancelling terms of the
    // elastic energy near F = I, StepProblem::energy_rounding): comparing energies is
    // meaningless there and
    // backtracking would stall, so the filtered step is taken as it is (the stopping test
    // is unchanged).
    const double predicted_decrease = -alpha * ws.gradient.dot(ws.direction);
    const double energy_noise =
        64.0 * std::numeric_limits<double>::epsilon() * (std::abs(energy) + 1.0) +
        problem.energy_rounding;
    if (predicted_decrease >= 0.0 && predicted_decrease < energy_noise) {
      blocked_add_scaled(z, alpha, ws.direction, ws.trial);
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
