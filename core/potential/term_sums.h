// The sums over the incremental potential's terms, written once for any problem type P that
// lists its terms as StepProblem does (for_each_node_term, for_each_mesh_term; term.h's
// contract): the value, the gradient and Hessian, the filters, explicit integration's force
// and the energies by kind. StepProblem's instances are in incremental_potential.cpp; a
// test's problem with one more term uses the same sums.
// Each sum adds the terms in the list's order, and splits its loops into blocks that depend
// on the mesh alone (work_blocks.h), so results do not depend on the thread count.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "potential/inertia.h"
#include "potential/step_caches.h"
#include "potential/term.h"
#include "potential/work_blocks.h"

namespace invfree {

template <class P>
TermPoint term_point(const P& p, StepCaches& caches, const VecX& z) {
  return {z, *p.mesh, p.x_start, caches};
}

// Inertia plus h^2 times every node term that is on, nodes [begin, end).
template <class P>
double node_energy_range(const P& p, const double* z, int begin, int end) {
  const double h2 = p.h * p.h;
  double e = 0.0;
  for (int i = begin; i < end; ++i) {
    const NodeState s = p.node_state(z, i);
    double potential = 0.0;
    p.for_each_node_term([&](const auto& term) {
      if (term.on) potential += term.value(s);
    });
    e += (p.inertia ? inertia_value(s, p.x_tilde[2 * i], p.x_tilde[2 * i + 1]) : 0.0) +
         h2 * potential;
  }
  return e;
}

template <class P>
double sum_energy(const P& p, StepCaches& caches, const VecX& z) {
  const int n = p.node_count();
  const BlockSplit nodes = split_blocks(n, kNodeBlock, kMaxBlocks);
  double partial[kMaxBlocks];
  run_blocks(nodes.blocks, [&](int b) {
    partial[b] = node_energy_range(p, z.data(), nodes.begin(b), nodes.end(b, n));
  });
  double e = 0.0;
  for (int b = 0; b < nodes.blocks; ++b) e += partial[b];
  const double h2 = p.h * p.h;
  const TermPoint at = term_point(p, caches, z);
  p.for_each_mesh_term([&](const auto& term) {
    if (term.on) e += term.value(at, term.scaled_by_h2 ? h2 : 1.0);
  });
  return std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
}

// Inertia and the node terms' derivatives for nodes [begin, end): each block owns its
// nodes' gradient entries (set, not added: these come first) and Hessian slots. The
// ceiling unknown's own entries are shared by every node: returned as block partials,
// summed in locals and stored once (the blocks' partials share a cache line: threads adding
// into them node by node would take it from each other at every node).
template <class P>
void add_node_derivatives(const P& p, const double* z, int begin, int end, Assembly& out,
                          double& ceiling_g_out, double& ceiling_h_out) {
  const double h2 = p.h * p.h;
  SparseHessian& hess = out.hessian;
  double* g = out.gradient.data();
  double* values = hess.values();
  const int* diag = hess.diagonal_slots.data();
  const bool with_ceiling = p.dof_count() > 2 * p.node_count();
  // A fixed ceiling is no unknown: its couplings stay zero (CeilingPenalty::add_derivatives
  // then needs to set only its diagonal, not to clear 2 slots per node).
  const bool ceiling_coupled = with_ceiling && !p.ceiling_penalty.fixed;
  double ceiling_g = 0.0, ceiling_h = 0.0;
  for (int i = begin; i < end; ++i) {
    const int ix = 2 * i, iy = 2 * i + 1;
    const NodeState s = p.node_state(z, i);
    NodeDerivatives d;
    if (p.inertia) set_inertia_derivatives(s, p.x_tilde[ix], p.x_tilde[iy], d);
    p.for_each_node_term([&](const auto& term) {
      if (term.on) term.add_derivatives(s, h2, d);
    });
    g[ix] = d.gx;
    g[iy] = d.gy;
    values[diag[ix]] += d.hxx;
    values[diag[iy]] += d.hyy;
    if (d.hxy != 0.0) {
      values[hess.node_xy_slots[ix]] += d.hxy;
      values[hess.node_xy_slots[iy]] += d.hxy;
    }
    if (with_ceiling) {
      ceiling_g += d.gc;
      ceiling_h += d.hcc;
      if (ceiling_coupled && d.hyc != 0.0) {
        values[hess.ceiling_slots[2 * i]] += d.hyc;
        values[hess.ceiling_slots[2 * i + 1]] += d.hyc;
      }
    }
  }
  ceiling_g_out = ceiling_g;
  ceiling_h_out = ceiling_h;
}

template <class P>
void add_all_node_derivatives(const P& p, const VecX& z, Assembly& out) {
  const int n = p.node_count();
  const BlockSplit nodes = split_blocks(n, kNodeBlock, kMaxBlocks);
  double ceiling_g[kMaxBlocks], ceiling_h[kMaxBlocks];
  thread_pool().run(nodes.blocks, [&](int b) {
    add_node_derivatives(p, z.data(), nodes.begin(b), nodes.end(b, n), out, ceiling_g[b],
                         ceiling_h[b]);
  });
  if (p.dof_count() == 2 * n) return;
  double gc = 0.0, hc = 0.0;
  for (int b = 0; b < nodes.blocks; ++b) {
    gc += ceiling_g[b];
    hc += ceiling_h[b];
  }
  out.gradient[2 * n] = gc;
  out.hessian.values()[out.hessian.diagonal_slots[2 * n]] += hc;
}

// Assembles once into `out`; returns false when a term outgrew the pattern.
template <class P>
bool assemble_terms(const P& p, StepCaches& caches, const VecX& z, Assembly& out) {
  const int nnz = static_cast<int>(out.hessian.matrix.nonZeros());
  const BlockSplit zero = split_blocks(nnz, 1 << 18, kMaxBlocks);
  double* values = out.hessian.values();
  thread_pool().run(zero.blocks, [&](int b) {
    std::fill(values + zero.begin(b), values + zero.end(b, nnz), 0.0);
  });
  out.hessian.couplings.clear();
  add_all_node_derivatives(p, z, out);
  const double h2 = p.h * p.h;
  const TermPoint at = term_point(p, caches, z);
  p.for_each_mesh_term([&](const auto& term) {
    if (term.on && !out.outgrown) term.add_derivatives(at, term.scaled_by_h2 ? h2 : 1.0, out);
  });
  return !out.outgrown;
}

template <class P>
double min_safe_step(const P& p, StepCaches& caches, const VecX& z, const VecX& dir) {
  // The node filters over fixed node blocks: a minimum, the same whatever the split.
  const int n = p.node_count();
  const BlockSplit blocks = split_blocks(n, kNodeBlock, kMaxBlocks);
  double block_alpha[kMaxBlocks];
  run_blocks(blocks.blocks, [&](int b) {
    double a = 1.0;
    p.for_each_node_term([&](const auto& term) {
      if constexpr (HasNodeMaxStep<std::decay_t<decltype(term)>>)
        if (term.on) a = term.max_step(z, n, blocks.begin(b), blocks.end(b, n), dir, a);
    });
    block_alpha[b] = a;
  });
  double alpha = 1.0;
  for (int b = 0; b < blocks.blocks; ++b) alpha = std::min(alpha, block_alpha[b]);
  const TermPoint at = term_point(p, caches, z);
  p.for_each_mesh_term([&](const auto& term) {
    if constexpr (HasMaxStep<std::decay_t<decltype(term)>>)
      if (term.on) alpha = term.max_step(at, dir, alpha);
  });
  return alpha;
}

template <class P>
double min_path_step(const P& p, StepCaches& caches, const VecX& z, const VecX& trial) {
  double fraction = 1.0;
  const TermPoint at = term_point(p, caches, z);
  p.for_each_mesh_term([&](const auto& term) {
    if constexpr (HasPathStep<std::decay_t<decltype(term)>>)
      if (term.on) fraction = std::min(fraction, term.path_step(at, trial));
  });
  return fraction;
}

// Explicit integration's gradient of the potential energy (minus the force) at x with
// velocities v: the whole-mesh terms' forces first, then each node's terms.
template <class P>
void explicit_gradient(const P& p, StepCaches& caches, const VecX& x, const VecX& v, double ceiling,
                       VecX& gradient) {
  const int n = p.node_count();
  gradient.setZero(2 * n);
  const TermPoint at = term_point(p, caches, x);
  p.for_each_mesh_term([&](const auto& term) {
    if constexpr (HasMeshExplicitForce<std::decay_t<decltype(term)>>)
      if (term.on) term.add_explicit_force(at, gradient);
  });
  for (int i = 0; i < n; ++i) {
    const NodeState node{i, x[2 * i], x[2 * i + 1], (*p.mass)[i], x[2 * i], ceiling};
    NodeDerivatives d;
    d.gx = gradient[2 * i];
    d.gy = gradient[2 * i + 1];
    p.for_each_node_term([&](const auto& term) {
      if (!term.on) return;
      if constexpr (HasNodeExplicitForce<std::decay_t<decltype(term)>>) {
        term.add_explicit_force(node, v.segment<2>(2 * i), p.h, d);
      } else {
        term.add_derivatives(node, 1.0, d);
      }
    });
    gradient[2 * i] = d.gx;
    gradient[2 * i + 1] = d.gy;
  }
}

// The terms' energies at z = [x; c] by kind, unscaled; control terms (the ceiling's
// penalty, the grab) are inputs, not energies of the bodies, and are left out.
template <class P>
void energies_by_kind(const P& p, StepCaches& caches, const VecX& z, EnergyBins& bins) {
  for (int i = 0; i < p.node_count(); ++i) {
    const NodeState s = p.node_state(z.data(), i);
    p.for_each_node_term([&](const auto& term) {
      if (term.on) bins[term.kind] += term.value(s);
    });
  }
  const TermPoint at = term_point(p, caches, z);
  p.for_each_mesh_term([&](const auto& term) {
    using T = std::decay_t<decltype(term)>;
    if (!term.on || T::kind == EnergyKind::Control) return;
    if constexpr (HasEnergyByKind<T>) {
      term.add_energy_by_kind(at, bins);
    } else {
      bins[T::kind] += term.value(at, 1.0);
    }
  });
}

}  // namespace invfree
