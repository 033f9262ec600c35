#include "potential/incremental_potential.h"

#include <algorithm>

#include "potential/term_sums.h"

namespace invfree {

namespace {

// The pattern of the mesh plus the node pairs the terms need now and those the pattern held
// already (contacts that come and go between iterations do not rebuild it each time),
// unless those outnumber the current ones by far (a fold that rolled on).
void rebuild_pattern(const StepProblem& p, std::vector<std::array<int, 2>> pairs,
                     SparseHessian& hess) {
  const size_t current = pairs.size();
  if (hess.extra_pairs.size() <= 4 * current + 64)
    pairs.insert(pairs.end(), hess.extra_pairs.begin(), hess.extra_pairs.end());
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  const int version = hess.pattern_version;
  hess = build_sparse_hessian(*p.mesh, p.ceiling.on, pairs);
  hess.pattern_version = version + 1;
}

}  // namespace

double ip_energy(const StepProblem& p, StepCaches& caches, const VecX& z) {
  return sum_energy(p, caches, z);
}

void ip_gradient_hessian(const StepProblem& p, StepCaches& caches, const VecX& z, VecX& gradient,
                         SparseHessian& hess) {
  if (gradient.size() != p.dof_count()) gradient.resize(p.dof_count());
  while (true) {
    Assembly out{gradient, hess};
    if (assemble_terms(p, caches, z, out)) break;
    rebuild_pattern(p, std::move(out.needed_pairs), hess);  // the values so far are stale
  }
  if (p.fixed.on) eliminate_fixed_dofs(p.fixed, gradient.data(), hess.values());
}

double largest_safe_step(const StepProblem& p, StepCaches& caches, const VecX& z,
                         const VecX& dir) {
  return min_safe_step(p, caches, z, dir);
}

double path_step(const StepProblem& p, StepCaches& caches, const VecX& z, const VecX& trial) {
  return min_path_step(p, caches, z, trial);
}

void begin_terms(const StepProblem& p, StepCaches& caches, const VecX& z) {
  const TermPoint at = term_point(p, caches, z);
  p.for_each_mesh_term([&](const auto& term) {
    if constexpr (HasBegin<std::decay_t<decltype(term)>>)
      if (term.on) term.begin(at);
  });
}

bool settle_controls(StepProblem& p, VecX& z) {
  bool moved = false;
  const int n = p.node_count();
  p.for_each_mesh_term([&](auto& term) {
    if constexpr (ControlTerm<std::decay_t<decltype(term)>>)
      if (term.on) moved = term.settle(n, z) || moved;
  });
  return moved;
}

bool controls_at_target(const StepProblem& p, const VecX& z, double tolerance) {
  bool at_target = true;
  const int n = p.node_count();
  p.for_each_mesh_term([&](const auto& term) {
    if constexpr (ControlTerm<std::decay_t<decltype(term)>>)
      if (term.on) at_target = at_target && term.at_target(n, z, tolerance);
  });
  return at_target;
}

void tighten_controls(StepProblem& p) {
  p.for_each_mesh_term([&](auto& term) {
    if constexpr (ControlTerm<std::decay_t<decltype(term)>>)
      if (term.on) term.tighten();
  });
}

double hessian_lower_bound(const StepProblem& p, double min_node_mass) {
  double lambda = min_node_mass;
  p.for_each_mesh_term([&](const auto& term) {
    if constexpr (ControlTerm<std::decay_t<decltype(term)>>)
      if (term.on) lambda = std::min(lambda, term.hessian_floor());
  });
  if (p.fixed.on) lambda = std::min(lambda, 1.0);  // the fixed nodes' identity rows
  return lambda;
}

}  // namespace invfree
