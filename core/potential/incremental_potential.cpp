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

// Room for the couplings a contact brings (SparseHessian::couplings), made once: a point-edge
// block couples its node with the edge's two nodes (4 blocks outside the pattern, both
// orientations), friction's as many again, a few edges per boundary node. A fold beyond
// that grows the list (an allocation, rare: once per new maximum).
void reserve_couplings(const StepProblem& p, SparseHessian& hess) {
  if (!hess.keep_couplings || !p.self_contact.on || hess.couplings.capacity() > 0) return;
  hess.couplings.reserve(16 * static_cast<size_t>(p.self_contact.boundary->node_count()) + 64);
}

// The couplings' rows and columns of fixed unknowns, zeroed as eliminate_fixed_dofs zeroes
// the pattern's (the identity rows are the pattern's diagonal).
void eliminate_fixed_couplings(const FixedDofs& f, std::vector<NodeCoupling>& couplings) {
  auto fixed = [&](int dof) { return std::binary_search(f.dofs.begin(), f.dofs.end(), dof); };
  for (NodeCoupling& c : couplings)
    for (int a = 0; a < 2; ++a) {
      if (fixed(2 * c.row_node + a)) c.block.row(a).setZero();
      if (fixed(2 * c.col_node + a)) c.block.col(a).setZero();
    }
}

}  // namespace

double ip_energy(const StepProblem& p, StepCaches& caches, const VecX& z) {
  return sum_energy(p, caches, z);
}

void ip_gradient_hessian(const StepProblem& p, StepCaches& caches, const VecX& z, VecX& gradient,
                         SparseHessian& hess) {
  if (gradient.size() != p.dof_count()) gradient.resize(p.dof_count());
  reserve_couplings(p, hess);
  while (true) {
    Assembly out{gradient, hess};
    if (assemble_terms(p, caches, z, out)) break;
    const bool keep = hess.keep_couplings;
    rebuild_pattern(p, std::move(out.needed_pairs), hess);  // the values so far are stale
    hess.keep_couplings = keep;
  }
  if (p.fixed.on) {
    eliminate_fixed_dofs(p.fixed, gradient.data(), hess.values());
    if (!hess.couplings.empty()) eliminate_fixed_couplings(p.fixed, hess.couplings);
  }
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
