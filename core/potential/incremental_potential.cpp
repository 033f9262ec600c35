#include "potential/incremental_potential.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "linalg/parallel.h"

namespace invfree {

namespace {

// Work is split into blocks whose size depends on the mesh alone (deterministic sums). A
// block is large enough (tens of microseconds) to be worth handing to another thread:
// waking one costs microseconds, more on a loaded machine. Small meshes run inline.
constexpr int kMaxBlocks = 256;           // per-block partial sums live on the stack
constexpr int kTriangleBlock = 4096;      // energy: triangles per block (at least)
constexpr int kNodeBlock = 8192;          // nodes per block (at least)
constexpr int kParallelTriangles = 2048;  // assembly: below this, colours run inline

// Inertia plus h^2 times every per-node term the scene switches on, nodes [begin, end).
double node_energy_range(const StepProblem& p, const double* z, int begin, int end) {
  const double h2 = p.h * p.h;
  double e = 0.0;
  for (int i = begin; i < end; ++i) {
    const NodeState s = p.node_state(z, i);
    double potential = 0.0;
    for_each_node_term(p, [&](const auto& term) {
      if (term.on) potential += term.value(s);
    });
    e += inertia_value(s, p.x_tilde[2 * i], p.x_tilde[2 * i + 1]) + h2 * potential;
  }
  return e;
}

// Gradient and Hessian of the per-node terms for nodes [begin, end). The ceiling unknown's
// own gradient and diagonal entries are shared by every node: returned as block partials.
void add_node_terms(const StepProblem& p, const double* z, int begin, int end, double* g,
                    SparseHessian& hess, double& ceiling_g, double& ceiling_h) {
  const double h2 = p.h * p.h;
  double* values = hess.values();
  const int* diag = hess.diagonal_slots.data();
  ceiling_g = ceiling_h = 0.0;
  for (int i = begin; i < end; ++i) {
    const int ix = 2 * i, iy = 2 * i + 1;
    const NodeState s = p.node_state(z, i);
    NodeDerivatives d;
    set_inertia_derivatives(s, p.x_tilde[ix], p.x_tilde[iy], d);
    for_each_node_term(p, [&](const auto& term) {
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
    if (p.ceiling.on) {
      ceiling_g += d.gc;
      ceiling_h += d.hcc;
      if (d.hyc != 0.0) {
        values[hess.ceiling_slots[2 * i]] += d.hyc;
        values[hess.ceiling_slots[2 * i + 1]] += d.hyc;
      }
    }
  }
}

// True when every node pair of every contact block is in the Hessian's pattern.
bool contact_blocks_fit(const std::vector<PointEdgeHessian>& blocks, const SparseHessian& hess) {
  for (const PointEdgeHessian& b : blocks)
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j)
        if (!has_node_block(hess, b.nodes[i], b.nodes[j])) return false;
  return true;
}

// The pattern of the mesh plus the node pairs of the current contact blocks and those the
// pattern held already (contacts that come and go between iterations do not rebuild it each
// time), unless those outnumber the current ones by far (a fold that rolled on).
void rebuild_pattern(const StepProblem& p, SparseHessian& hess) {
  std::vector<std::array<int, 2>> pairs;
  for (const PointEdgeHessian& b : p.self_contact.cache->hessians)
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j) {
        const int u = b.nodes[i], v = b.nodes[j];
        if (u != v) pairs.push_back({std::min(u, v), std::max(u, v)});
      }
  const size_t current = pairs.size();
  if (hess.extra_pairs.size() <= 4 * current + 64)
    pairs.insert(pairs.end(), hess.extra_pairs.begin(), hess.extra_pairs.end());
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  const int version = hess.pattern_version;
  hess = build_sparse_hessian(*p.mesh, p.ceiling.on, pairs);
  hess.pattern_version = version + 1;
}

void scatter_contact_blocks(const std::vector<PointEdgeHessian>& blocks, SparseHessian& hess) {
  for (const PointEdgeHessian& b : blocks)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        add_node_block(hess, b.nodes[i], b.nodes[j], b.hessian.block<2, 2>(2 * i, 2 * j));
}

}  // namespace

double ip_energy(const StepProblem& p, const VecX& z) {
  const int n = p.node_count();
  const int nt = p.elasticity.on ? p.mesh->triangle_count() : 0;
  const double* zp = z.data();
  const BlockSplit tri = split_blocks(nt, kTriangleBlock, kMaxBlocks);
  const BlockSplit nodes = split_blocks(n, kNodeBlock, kMaxBlocks);
  double partial[2 * kMaxBlocks];
  visit_model(p.elasticity.model, [&](auto m) {
    using M = decltype(m);
    auto block = [&](int task) {
      if (task < tri.blocks) {
        partial[task] = elastic_energy_range<M>(*p.mesh, p.elasticity.lame, zp, tri.begin(task),
                                                tri.end(task, nt), p.elasticity.triangle_lame);
      } else {
        const int b = task - tri.blocks;
        partial[task] = node_energy_range(p, zp, nodes.begin(b), nodes.end(b, n));
      }
    };
    const int tasks = tri.blocks + nodes.blocks;
    if (tri.blocks >= 2) {
      thread_pool().run(tasks, block);
    } else {
      for (int task = 0; task < tasks; ++task) block(task);
    }
  });
  double elastic = 0.0, rest = 0.0;
  for (int b = 0; b < tri.blocks; ++b) elastic += partial[b];
  for (int b = 0; b < nodes.blocks; ++b) rest += partial[tri.blocks + b];
  const double h2 = p.h * p.h;
  double e = h2 * elastic + rest;
  if (p.ceiling.on) e += p.ceiling_penalty.value(z[2 * n]);
  if (p.pull.on) e += p.pull.value(z.segment<2>(2 * p.pull.node), h2);
  if (p.springs.on) e += h2 * mass_spring_energy(p.springs, zp);
  if (p.self_contact.on) e += h2 * self_contact_value(p.self_contact, z, p.x_start);
  return std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
}

void ip_gradient_hessian(const StepProblem& p, const VecX& z, VecX& gradient, SparseHessian& hess) {
  const int n = p.node_count();
  const double h2 = p.h * p.h;
  if (gradient.size() != p.dof_count()) gradient.resize(p.dof_count());
  double* g = gradient.data();
  const double* zp = z.data();
  ThreadPool& pool = thread_pool();

  // Zero the values, then the per-node terms (each block owns its nodes' slots).
  const int nnz = static_cast<int>(hess.matrix.nonZeros());
  const BlockSplit zero = split_blocks(nnz, 1 << 18, kMaxBlocks);
  double* values = hess.values();
  pool.run(zero.blocks,
           [&](int b) { std::fill(values + zero.begin(b), values + zero.end(b, nnz), 0.0); });
  const BlockSplit nodes = split_blocks(n, kNodeBlock, kMaxBlocks);
  double ceiling_g[kMaxBlocks], ceiling_h[kMaxBlocks];
  pool.run(nodes.blocks, [&](int b) {
    add_node_terms(p, zp, nodes.begin(b), nodes.end(b, n), g, hess, ceiling_g[b], ceiling_h[b]);
  });

  // Elasticity, one colour at a time: no two chunks of a colour share a node (no locks).
  const bool parallel = p.mesh->triangle_count() >= kParallelTriangles;
  if (p.elasticity.on)
    visit_model(p.elasticity.model, [&](auto m) {
      using M = decltype(m);
      for (int colour = 0; colour < hess.colour_count(); ++colour) {
        const int first = hess.colour_begin[colour], count = hess.colour_begin[colour + 1] - first;
        auto chunk = [&](int k) {
          const int begin = hess.chunk_order[first + k] * hess.chunk_size;
          const int end = std::min(p.mesh->triangle_count(), begin + hess.chunk_size);
          add_elastic_derivatives_range<M>(*p.mesh, p.elasticity, zp, begin, end, h2, g, hess);
        };
        if (parallel) {
          pool.run(count, chunk);
        } else {
          for (int k = 0; k < count; ++k) chunk(k);
        }
      }
    });

  if (p.springs.on) add_mass_spring_derivatives(p.springs, zp, h2, g, values);

  if (p.pull.on) {
    const int ix = 2 * p.pull.node, iy = ix + 1;
    p.pull.add_derivatives(z.segment<2>(ix), h2, g[ix], g[iy], values[hess.diagonal_slots[ix]],
                           values[hess.diagonal_slots[iy]]);
  }

  if (p.self_contact.on) {
    self_contact_derivatives(p.self_contact, z, p.x_start, h2, gradient);
    if (!contact_blocks_fit(p.self_contact.cache->hessians, hess)) {
      // A contact outside the pattern: rebuild it and assemble again (the values so far
      // live in the old matrix).
      rebuild_pattern(p, hess);
      ip_gradient_hessian(p, z, gradient, hess);
      return;
    }
    scatter_contact_blocks(p.self_contact.cache->hessians, hess);
  }

  if (p.ceiling.on) {
    const int c = 2 * n;
    double gc = 0.0, hc = 0.0;
    for (int b = 0; b < nodes.blocks; ++b) {
      gc += ceiling_g[b];
      hc += ceiling_h[b];
    }
    g[c] = gc + p.ceiling_penalty.gradient(z[c]);
    values[hess.diagonal_slots[c]] += hc + p.ceiling_penalty.stiffness;
    if (p.ceiling_penalty.fixed) {
      g[c] = 0.0;
      hess.eliminate_ceiling();
    }
  }
  if (p.fixed.on) eliminate_fixed_dofs(p.fixed, g, values);
}

double largest_feasible_step(const StepProblem& p, const VecX& z, const VecX& dir) {
  double alpha = plane_step(p.ground, p.ceiling, p.node_count(), z, dir);
  if (p.elasticity.filters_inversions())
    alpha = std::min(alpha, inversion_free_step(*p.mesh, z, dir));
  return alpha;
}

}  // namespace invfree
