#include "linalg/sparse_hessian.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "linalg/blocked_vector_ops.h"

namespace invfree {

int sparse_slot(const Eigen::SparseMatrix<double>& m, int row, int col) {
  const int* inner = m.innerIndexPtr();
  const int begin = m.outerIndexPtr()[col], end = m.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(inner + begin, inner + end, row);
  if (it == inner + end || *it != row) throw std::logic_error("sparse pattern is missing an entry");
  return static_cast<int>(it - inner);
}

namespace {
int find_slot(const Eigen::SparseMatrix<double>& m, int row, int col) {
  return sparse_slot(m, row, col);
}
// Greedy colouring of the triangle chunks: each chunk takes the lowest colour not used by
// an earlier chunk sharing one of its nodes (a per-node bit mask of the colours touching
// it). On the square mesh, chunks are strips of rows and two or three colours suffice.
void build_assembly_plan(const Mesh& mesh, SparseHessian& h) {
  constexpr int kChunk = 128;  // fixed: the plan must not depend on the thread count
  const int nt = mesh.triangle_count();
  const int chunks = (nt + kChunk - 1) / kChunk;
  std::vector<std::uint64_t> node_colours(mesh.node_count(), 0);
  std::vector<int> colour(chunks, 0);
  int colours = chunks > 0 ? 1 : 0;
  for (int k = 0; k < chunks; ++k) {
    const int begin = k * kChunk, end = std::min(nt, begin + kChunk);
    std::uint64_t used = 0;
    for (int t = begin; t < end; ++t)
      for (int v : mesh.triangles[t]) used |= node_colours[v];
    int c = 0;
    while (c < 64 && (used >> c) & 1u) ++c;
    if (c == 64) throw std::logic_error("assembly plan: more than 64 colours");
    colour[k] = c;
    colours = std::max(colours, c + 1);
    for (int t = begin; t < end; ++t)
      for (int v : mesh.triangles[t]) node_colours[v] |= std::uint64_t{1} << c;
  }
  h.chunk_size = kChunk;
  h.colour_begin.assign(colours + 1, 0);
  for (int k = 0; k < chunks; ++k) ++h.colour_begin[colour[k] + 1];
  for (int c = 0; c < colours; ++c) h.colour_begin[c + 1] += h.colour_begin[c];
  h.chunk_order.resize(chunks);
  std::vector<int> fill(h.colour_begin.begin(), h.colour_begin.end() - 1);
  for (int k = 0; k < chunks; ++k) h.chunk_order[fill[colour[k]]++] = k;
}

}  // namespace

// The pattern is made of 2x2 node blocks: node j's two columns hold, for each of its
// neighbours i (itself, the nodes it shares a triangle with, its extra pairs) in
// ascending order, the rows 2i and 2i+1; with a ceiling, each y column ends with the
// ceiling's row c, and column c holds every node's y row, then c. Written straight into
// the compressed arrays, since a list of every entry the triangles touch would hold 4.7 M
// at n_seg 256 (75 MB, and a sort); a triangle's 36 slots come from its 9 node pairs.
SparseHessian build_sparse_hessian(const Mesh& mesh, bool with_ceiling,
                                   std::span<const std::array<int, 2>> extra_pairs) {
  const int n_nodes = mesh.node_count();
  const int n_dof = 2 * n_nodes + (with_ceiling ? 1 : 0);
  const int c = 2 * n_nodes;

  // Each node's neighbours, with repeats first, then sorted and made unique in place.
  std::vector<int> begin(n_nodes + 1, 0);
  for (int i = 0; i < n_nodes; ++i) begin[i + 1] = 1;
  for (const auto& tri : mesh.triangles)
    for (int v : tri) begin[v + 1] += 2;
  for (const auto& pair : extra_pairs) {
    ++begin[pair[0] + 1];
    ++begin[pair[1] + 1];
  }
  for (int i = 0; i < n_nodes; ++i) begin[i + 1] += begin[i];
  std::vector<int> neighbours(begin[n_nodes]);
  {
    std::vector<int> fill(begin.begin(), begin.end() - 1);
    for (int i = 0; i < n_nodes; ++i) neighbours[fill[i]++] = i;
    for (const auto& tri : mesh.triangles)
      for (int a = 0; a < 3; ++a) {
        neighbours[fill[tri[a]]++] = tri[(a + 1) % 3];
        neighbours[fill[tri[a]]++] = tri[(a + 2) % 3];
      }
    for (const auto& pair : extra_pairs) {
      neighbours[fill[pair[0]]++] = pair[1];
      neighbours[fill[pair[1]]++] = pair[0];
    }
  }
  std::vector<int> adj_begin(n_nodes + 1, 0);
  int kept = 0;
  for (int i = 0; i < n_nodes; ++i) {
    auto first = neighbours.begin() + begin[i], last = neighbours.begin() + begin[i + 1];
    std::sort(first, last);
    last = std::unique(first, last);
    adj_begin[i] = kept;
    for (auto it = first; it != last; ++it) neighbours[kept++] = *it;
  }
  adj_begin[n_nodes] = kept;
  const int* adj = neighbours.data();
  auto degree = [&](int j) { return adj_begin[j + 1] - adj_begin[j]; };
  // Position of node i among node j's neighbours.
  auto rank = [&](int i, int j) {
    return static_cast<int>(std::lower_bound(adj + adj_begin[j], adj + adj_begin[j + 1], i) -
                            (adj + adj_begin[j]));
  };

  SparseHessian h;
  h.matrix.resize(n_dof, n_dof);
  int* outer = h.matrix.outerIndexPtr();
  outer[0] = 0;
  for (int j = 0; j < n_nodes; ++j) {
    outer[2 * j + 1] = outer[2 * j] + 2 * degree(j);
    outer[2 * j + 2] = outer[2 * j + 1] + 2 * degree(j) + (with_ceiling ? 1 : 0);
  }
  if (with_ceiling) outer[c + 1] = outer[c] + n_nodes + 1;
  h.matrix.resizeNonZeros(outer[n_dof]);
  int* inner = h.matrix.innerIndexPtr();  // (the values are zeroed by set_zero, below)
  for (int j = 0; j < n_nodes; ++j)
    for (int b = 0; b < 2; ++b) {
      int p = outer[2 * j + b];
      for (int k = adj_begin[j]; k < adj_begin[j + 1]; ++k) {
        inner[p++] = 2 * adj[k];
        inner[p++] = 2 * adj[k] + 1;
      }
      if (b == 1 && with_ceiling) inner[p++] = c;
    }
  if (with_ceiling) {
    int p = outer[c];
    for (int i = 0; i < n_nodes; ++i) inner[p++] = 2 * i + 1;
    inner[p] = c;
  }

  h.triangle_slots.resize(mesh.triangles.size() * 36);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (int bn = 0; bn < 3; ++bn)
      for (int an = 0; an < 3; ++an) {
        const int k = rank(tri[an], tri[bn]);
        for (int bc = 0; bc < 2; ++bc)
          for (int ac = 0; ac < 2; ++ac)
            h.triangle_slots[t * 36 + (2 * an + ac) * 6 + 2 * bn + bc] =
                outer[2 * tri[bn] + bc] + 2 * k + ac;
      }
  }
  h.diagonal_slots.resize(n_dof);
  h.node_xy_slots.resize(2 * n_nodes);
  for (int i = 0; i < n_nodes; ++i) {
    const int k = rank(i, i);
    h.diagonal_slots[2 * i] = outer[2 * i] + 2 * k;
    h.diagonal_slots[2 * i + 1] = outer[2 * i + 1] + 2 * k + 1;
    h.node_xy_slots[2 * i] = outer[2 * i + 1] + 2 * k;      // (2i, 2i+1)
    h.node_xy_slots[2 * i + 1] = outer[2 * i] + 2 * k + 1;  // (2i+1, 2i)
  }
  if (with_ceiling) {
    h.diagonal_slots[c] = outer[c] + n_nodes;
    h.ceiling_dof = c;
    h.ceiling_slots.resize(2 * n_nodes);
    for (int i = 0; i < n_nodes; ++i) {
      h.ceiling_slots[2 * i] = outer[c] + i;              // (2i+1, c)
      h.ceiling_slots[2 * i + 1] = outer[2 * i + 2] - 1;  // (c, 2i+1)
    }
  }
  build_assembly_plan(mesh, h);
  h.extra_pairs.assign(extra_pairs.begin(), extra_pairs.end());
  h.set_zero();
  return h;
}

bool pattern_has_node_block(const SparseHessian& h, int i, int j) {
  const Eigen::SparseMatrix<double>& m = h.matrix;
  const int* inner = m.innerIndexPtr();
  const int begin = m.outerIndexPtr()[2 * j], end = m.outerIndexPtr()[2 * j + 1];
  return std::binary_search(inner + begin, inner + end, 2 * i);
}

bool has_node_block(const SparseHessian& h, int i, int j) {
  return h.keep_couplings || pattern_has_node_block(h, i, j);
}

void add_node_block(SparseHessian& h, int i, int j, const Mat2& block) {
  if (h.keep_couplings && !pattern_has_node_block(h, i, j)) {
    // A zero block (a point-edge pair in a point-point regime leaves the far endpoint
    // uncoupled) adds nothing: not listed, so its nodes do not join PCG's correction.
    if (!block.isZero(0.0)) h.couplings.push_back({i, j, block});
    return;
  }
  double* v = h.values();
  for (int b = 0; b < 2; ++b)
    for (int a = 0; a < 2; ++a) v[find_slot(h.matrix, 2 * i + a, 2 * j + b)] += block(a, b);
}

void multiply_hessian(const SparseHessian& h, const VecX& v, VecX& y) {
  multiply_symmetric(h.matrix, h.couplings, v, y);
}

}  // namespace invfree
