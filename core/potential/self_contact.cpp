#include "potential/self_contact.h"

#include <algorithm>

#include "collision/broad_phase.h"
#include "potential/step_caches.h"
#include "solver/ccd.h"

namespace invfree {

namespace {

// True when every node pair of every contact block is in the Hessian's pattern.
bool blocks_fit(const std::vector<PointEdgeHessian>& blocks, const SparseHessian& hess) {
  for (const PointEdgeHessian& b : blocks)
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j)
        if (!has_node_block(hess, b.nodes[i], b.nodes[j])) return false;
  return true;
}

void list_block_pairs(const std::vector<PointEdgeHessian>& blocks,
                      std::vector<std::array<int, 2>>& pairs) {
  for (const PointEdgeHessian& b : blocks)
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j) {
        const int u = b.nodes[i], v = b.nodes[j];
        if (u != v) pairs.push_back({std::min(u, v), std::max(u, v)});
      }
}

void scatter_blocks(const std::vector<PointEdgeHessian>& blocks, SparseHessian& hess) {
  for (const PointEdgeHessian& b : blocks)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        add_node_block(hess, b.nodes[i], b.nodes[j], b.hessian.block<2, 2>(2 * i, 2 * j));
}

}  // namespace

void reserve_self_contact(const Boundary& boundary, SelfContactCache& cache, BroadPhaseGrid& grid) {
  const size_t ne = boundary.edges.size(), nb = boundary.nodes.size();
  grid.edge_boxes.reserve(ne);
  grid.edge_cells.reserve(ne);
  grid.cell_start.reserve(12 * (ne + 1) + 2);  // at most 3 x 4 (ne + 1) + 1 cells
  grid.cell_edges.reserve(16 * ne);
  reserve_candidates(static_cast<int>(nb), 32, grid);  // as clearance.pairs
  cache.pairs.reserve(16 * nb);
  cache.near.reserve(16 * nb);
  cache.pair_sums.reserve(16 * nb);
  cache.clearance.pairs.reserve(32 * nb);
  cache.clearance.pair_slack.reserve(32 * nb);
  cache.clearance.at.resize(2 * static_cast<long>(nb));
  cache.clearance.lo.resize(nb);
  cache.clearance.hi.resize(nb);
}

double SelfContact::value(const TermPoint& at, double scale) const {
  SelfContactCache& cache = at.caches.contact;
  if (cache.pairs.empty() && cache.friction.empty()) return 0.0;
  const SelfContactTimer timer{cache.ms};
  double e = self_contact_energy(*boundary, *rest, cache.pairs, at.z, params, &cache.pair_sums);
  if (!cache.friction.empty()) e += self_friction_energy(cache.friction, at.z, at.x_start, eps_u);
  return scale * e;
}

void SelfContact::add_derivatives(const TermPoint& at, double scale, Assembly& out) const {
  SelfContactCache& cache = at.caches.contact;
  cache.hessians.clear();
  if (cache.pairs.empty() && cache.friction.empty()) return;
  const SelfContactTimer timer{cache.ms};
  add_self_contact_gradient_hessian(*boundary, *rest, cache.pairs, at.z, params, scale,
                                    out.gradient, cache.hessians, &cache.pair_sums);
  if (!cache.friction.empty())
    add_self_friction_gradient_hessian(cache.friction, at.z, at.x_start, eps_u, scale, out.gradient,
                                       cache.hessians);
  if (!blocks_fit(cache.hessians, out.hessian)) {
    out.outgrown = true;
    list_block_pairs(cache.hessians, out.needed_pairs);
    return;
  }
  scatter_blocks(cache.hessians, out.hessian);
}

double SelfContact::max_step(const TermPoint& at, const VecX& dir, double alpha) const {
  if (!(alpha > 0.0)) return alpha;
  SelfContactCache& cache = at.caches.contact;
  const SelfContactTimer timer{cache.ms};
  if (!clear_candidates(at, &dir, alpha))
    swept_point_edge_candidates(*boundary, at.z, dir, alpha, params.dhat, at.caches.grid,
                                cache.pairs);
  if (!ccd || cache.pairs.empty()) return alpha;  // nothing within dhat: nothing to stop
  return self_contact_step(*boundary, cache.pairs, at.z, dir, alpha);
}

double SelfContact::path_step(const TermPoint& at, const VecX& trial) const {
  SelfContactCache& cache = at.caches.contact;
  if (!ccd || cache.pairs.empty()) return 1.0;
  const SelfContactTimer timer{cache.ms};
  at.caches.scratch = trial - at.z;
  return self_contact_step(*boundary, cache.pairs, at.z, at.caches.scratch, 1.0);
}

void SelfContact::begin(const TermPoint& at) const {
  SelfContactCache& cache = at.caches.contact;
  const SelfContactTimer timer{cache.ms};
  if (!clear_candidates(at, nullptr, 0.0))
    point_edge_candidates(*boundary, at.z, params.dhat, at.caches.grid, cache.pairs);
}

bool SelfContact::clear_candidates(const TermPoint& at, const VecX* dir, double alpha) const {
  SelfContactCache& cache = at.caches.contact;
  const double m = clearance_motion(*boundary, cache.clearance, at.z, dir, alpha);
  if (is_clear(cache.clearance, params.dhat, m)) {
    cache.pairs.clear();
    return true;
  }
  return near_pairs(*boundary, cache.clearance, params.dhat, m, cache.pairs);
}

void SelfContact::add_energy_by_kind(const TermPoint& at, EnergyBins& bins) const {
  const SelfContactCache& cache = at.caches.contact;
  bins[EnergyKind::Contact] += self_contact_energy(*boundary, *rest, cache.pairs, at.z, params);
  if (!cache.friction.empty())
    bins[EnergyKind::Friction] += self_friction_energy(cache.friction, at.z, at.x_start, eps_u);
}

}  // namespace invfree
