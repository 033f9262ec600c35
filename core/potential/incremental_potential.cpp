#include "potential/incremental_potential.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "linalg/parallel.h"
#include "material/models.h"
#include "material/triangle_elasticity.h"

namespace invfree {

namespace {

Vec2 node(const VecX& x, int i) {
  return x.segment<2>(2 * i);
}

Mat2 triangle_f(const Mesh& mesh, const VecX& x, int t) {
  const auto& tri = mesh.triangles[t];
  return deformation_gradient(node(x, tri[0]), node(x, tri[1]), node(x, tri[2]),
                              mesh.rest_shape_inverse[t]);
}

template <class M>
double elastic_energy_for(const Mesh& mesh, const Lame& lame, const VecX& x) {
  double e = 0.0;
  for (int t = 0; t < mesh.triangle_count(); ++t)
    e += mesh.rest_area[t] * M::energy_density(triangle_f(mesh, x, t), lame);
  return e;
}

template <class M>
void add_elastic_gradient_for(const Mesh& mesh, const Lame& lame, const VecX& x, double scale,
                              VecX& g) {
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Mat46 dFdx = deformation_gradient_jacobian(mesh.rest_shape_inverse[t]);
    const Vec6 gt = TriangleElasticity<M>::gradient(triangle_f(mesh, x, t), dFdx,
                                                    scale * mesh.rest_area[t], lame);
    const auto& tri = mesh.triangles[t];
    for (int a = 0; a < 3; ++a) g.segment<2>(2 * tri[a]) += gt.segment<2>(2 * a);
  }
}

}  // namespace

double elastic_energy(const Mesh& mesh, Model model, const Lame& lame, const VecX& x) {
  return visit_model(model, [&](auto m) { return elastic_energy_for<decltype(m)>(mesh, lame, x); });
}

void add_elastic_gradient(const Mesh& mesh, Model model, const Lame& lame, const VecX& x,
                          double scale, VecX& gradient) {
  visit_model(model, [&](auto m) {
    add_elastic_gradient_for<decltype(m)>(mesh, lame, x, scale, gradient);
  });
}

namespace {

// Work is split into blocks whose size depends on the mesh alone (deterministic sums). A
// block is large enough (tens of microseconds) to be worth handing to another thread:
// waking one costs microseconds, more on a loaded machine. Small meshes run inline.
constexpr int kMaxBlocks = 256;           // per-block partial sums live on the stack
constexpr int kTriangleBlock = 4096;      // energy: triangles per block (at least)
constexpr int kNodeBlock = 8192;          // nodes per block (at least)
constexpr int kParallelTriangles = 2048;  // assembly: below this, colours run inline

Vec2 node_at(const double* x, int i) {
  return {x[2 * i], x[2 * i + 1]};
}

template <class M>
double triangle_energy_range(const Mesh& mesh, const Lame& lame, const double* x, int begin,
                             int end) {
  double e = 0.0;
  for (int t = begin; t < end; ++t) {
    const auto& tri = mesh.triangles[t];
    const Mat2 F = deformation_gradient(node_at(x, tri[0]), node_at(x, tri[1]), node_at(x, tri[2]),
                                        mesh.rest_shape_inverse[t]);
    e += mesh.rest_area[t] * M::energy_density(F, lame);
  }
  return e;
}

// Inertia plus h^2 times every per-node potential the scene switches on.
double node_energy_range(const StepProblem& p, const double* z, int begin, int end) {
  const auto& mass = *p.mass;
  const double h2 = p.h * p.h;
  const int c = 2 * p.node_count();
  double e = 0.0;
  for (int i = begin; i < end; ++i) {
    const double dx = z[2 * i] - p.x_tilde[2 * i], dy = z[2 * i + 1] - p.x_tilde[2 * i + 1];
    double potential = 0.0;
    if (p.gravity_on)
      potential -= mass[i] * (p.gravity.x() * z[2 * i] + p.gravity.y() * z[2 * i + 1]);
    if (p.ground_on) potential += barrier_value(z[2 * i + 1] - p.ground_y, p.barrier);
    if (p.friction_on && p.friction_weight[i] > 0.0)
      potential +=
          friction_value(z[2 * i] - p.x_start[2 * i], p.friction_weight[i], p.friction_eps_u);
    if (p.ceiling_on) potential += barrier_value(z[c] - z[2 * i + 1], p.barrier);
    e += 0.5 * mass[i] * (dx * dx + dy * dy) + h2 * potential;
  }
  return e;
}

}  // namespace

double ip_energy(const StepProblem& p, const VecX& z) {
  const int n = p.node_count();
  const int nt = p.mesh->triangle_count();
  const double* zp = z.data();
  const BlockSplit tri = split_blocks(nt, kTriangleBlock, kMaxBlocks);
  const BlockSplit nodes = split_blocks(n, kNodeBlock, kMaxBlocks);
  double partial[2 * kMaxBlocks];
  visit_model(p.model, [&](auto m) {
    using M = decltype(m);
    auto block = [&](int task) {
      if (task < tri.blocks) {
        partial[task] =
            triangle_energy_range<M>(*p.mesh, p.lame, zp, tri.begin(task), tri.end(task, nt));
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
  double e = p.h * p.h * elastic + rest;
  if (p.ceiling_on) {
    const double gap = z[2 * n] - p.ceiling_target;
    e += 0.5 * p.ceiling_stiffness * gap * gap;
  }
  if (p.pull_on) {
    const Vec2 d = node_at(zp, p.pull_node) - p.pull_target;
    e += 0.5 * p.h * p.h * p.pull_stiffness * d.squaredNorm();
  }
  return std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
}

namespace {

// Per-node terms of the gradient and Hessian for nodes [begin, end): inertia, gravity,
// ground barrier, friction and the ceiling barrier. The ceiling unknown's own gradient
// and diagonal entries are shared by every node: they are returned as block partials.
void add_node_terms(const StepProblem& p, const double* z, int begin, int end, double* g,
                    SparseHessian& hess, double& ceiling_g, double& ceiling_h) {
  const auto& mass = *p.mass;
  const double h2 = p.h * p.h;
  double* values = hess.values();
  const int* diag = hess.diagonal_slots.data();
  const int c = 2 * p.node_count();
  ceiling_g = ceiling_h = 0.0;
  for (int i = begin; i < end; ++i) {
    const int ix = 2 * i, iy = 2 * i + 1;
    g[ix] = mass[i] * (z[ix] - p.x_tilde[ix]);
    g[iy] = mass[i] * (z[iy] - p.x_tilde[iy]);
    values[diag[ix]] += mass[i];
    values[diag[iy]] += mass[i];
    if (p.gravity_on) {
      g[ix] -= h2 * mass[i] * p.gravity.x();
      g[iy] -= h2 * mass[i] * p.gravity.y();
    }
    if (p.ground_on) {
      const double d = z[iy] - p.ground_y;
      if (d < p.barrier.dhat) {
        g[iy] += h2 * barrier_derivative(d, p.barrier);
        values[diag[iy]] += h2 * barrier_second_derivative(d, p.barrier);
      }
    }
    if (p.friction_on) {
      const double w = p.friction_weight[i];
      if (w > 0.0) {
        const double u = z[ix] - p.x_start[ix];
        g[ix] += h2 * friction_derivative(u, w, p.friction_eps_u);
        values[diag[ix]] += h2 * friction_second_derivative(u, w, p.friction_eps_u);
      }
    }
    if (p.ceiling_on) {
      const double d = z[c] - z[iy];
      if (d < p.barrier.dhat) {
        // b(c - y_i): d/dc = b', d/dy_i = -b'; Hessian b'' [1 -1; -1 1] on (y_i, c).
        const double d1 = h2 * barrier_derivative(d, p.barrier);
        const double d2 = h2 * barrier_second_derivative(d, p.barrier);
        g[iy] -= d1;
        ceiling_g += d1;
        values[diag[iy]] += d2;
        ceiling_h += d2;
        values[hess.ceiling_slots[2 * i]] -= d2;
        values[hess.ceiling_slots[2 * i + 1]] -= d2;
      }
    }
  }
}

// Gradient and Hessian of every triangle of the chunks of one colour, scattered into the
// gradient and the fixed pattern (no two chunks of a colour share a node: no locks).
template <class M>
void add_triangle_chunk(const StepProblem& p, const double* z, int chunk, double h2, double* g,
                        SparseHessian& hess) {
  const Mesh& mesh = *p.mesh;
  const int begin = chunk * hess.chunk_size;
  const int end = std::min(mesh.triangle_count(), begin + hess.chunk_size);
  double* values = hess.values();
  Vec6 gt;
  Mat6 ht;
  for (int t = begin; t < end; ++t) {
    const auto& tri = mesh.triangles[t];
    const Mat2& IB = mesh.rest_shape_inverse[t];
    const Mat2 F =
        deformation_gradient(node_at(z, tri[0]), node_at(z, tri[1]), node_at(z, tri[2]), IB);
    TriangleElasticity<M>::gradient_hessian(F, IB, h2 * mesh.rest_area[t], p.lame, p.projection, gt,
                                            ht);
    for (int a = 0; a < 3; ++a) {
      g[2 * tri[a]] += gt[2 * a];
      g[2 * tri[a] + 1] += gt[2 * a + 1];
    }
    const int* slots = &hess.triangle_slots[36 * static_cast<size_t>(t)];
    const double* local = ht.data();  // column-major; ht is symmetric, so row-major alike
    for (int k = 0; k < 36; ++k) values[slots[k]] += local[k];
  }
}

}  // namespace

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

  const bool parallel = p.mesh->triangle_count() >= kParallelTriangles;
  visit_model(p.model, [&](auto m) {
    using M = decltype(m);
    for (int colour = 0; colour < hess.colour_count(); ++colour) {
      const int first = hess.colour_begin[colour], count = hess.colour_begin[colour + 1] - first;
      auto chunk = [&](int k) {
        add_triangle_chunk<M>(p, zp, hess.chunk_order[first + k], h2, g, hess);
      };
      if (parallel) {
        pool.run(count, chunk);
      } else {
        for (int k = 0; k < count; ++k) chunk(k);
      }
    }
  });

  if (p.pull_on) {
    const int ix = 2 * p.pull_node, iy = ix + 1;
    const double k = h2 * p.pull_stiffness;
    g[ix] += k * (z[ix] - p.pull_target.x());
    g[iy] += k * (z[iy] - p.pull_target.y());
    values[hess.diagonal_slots[ix]] += k;
    values[hess.diagonal_slots[iy]] += k;
  }

  if (p.ceiling_on) {
    const int c = 2 * n;
    double gc = 0.0, hc = 0.0;
    for (int b = 0; b < nodes.blocks; ++b) {
      gc += ceiling_g[b];
      hc += ceiling_h[b];
    }
    g[c] = gc + p.ceiling_stiffness * (z[c] - p.ceiling_target);
    values[hess.diagonal_slots[c]] += hc + p.ceiling_stiffness;
    if (p.ceiling_fixed) {
      g[c] = 0.0;
      hess.eliminate_ceiling();
    }
  }
}

}  // namespace invfree
