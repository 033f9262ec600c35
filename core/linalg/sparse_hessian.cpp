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

SparseHessian build_sparse_hessian(const Mesh& mesh, bool with_ceiling,
                                   std::span<const std::array<int, 2>> extra_pairs) {
  const int n_nodes = mesh.node_count();
  const int n_dof = 2 * n_nodes + (with_ceiling ? 1 : 0);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(mesh.triangles.size() * 36 + n_dof + (with_ceiling ? 2 * n_nodes : 0));
  for (const auto& tri : mesh.triangles)
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b)
        entries.emplace_back(2 * tri[a / 2] + a % 2, 2 * tri[b / 2] + b % 2, 0.0);
  for (int i = 0; i < n_dof; ++i) entries.emplace_back(i, i, 0.0);
  for (int i = 0; i < n_nodes; ++i) {  // (within a triangle's block already, unless isolated)
    entries.emplace_back(2 * i, 2 * i + 1, 0.0);
    entries.emplace_back(2 * i + 1, 2 * i, 0.0);
  }
  for (const auto& pair : extra_pairs)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        entries.emplace_back(2 * pair[a / 2] + a % 2, 2 * pair[b / 2] + b % 2, 0.0);
  const int c = 2 * n_nodes;
  if (with_ceiling)
    for (int i = 0; i < n_nodes; ++i) {
      entries.emplace_back(2 * i + 1, c, 0.0);
      entries.emplace_back(c, 2 * i + 1, 0.0);
    }
  SparseHessian h;
  h.matrix.resize(n_dof, n_dof);
  h.matrix.setFromTriplets(entries.begin(), entries.end());
  h.matrix.makeCompressed();

  h.triangle_slots.resize(mesh.triangles.size() * 36);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b)
        h.triangle_slots[t * 36 + a * 6 + b] =
            find_slot(h.matrix, 2 * tri[a / 2] + a % 2, 2 * tri[b / 2] + b % 2);
  }
  h.diagonal_slots.resize(n_dof);
  for (int i = 0; i < n_dof; ++i) h.diagonal_slots[i] = find_slot(h.matrix, i, i);
  h.node_xy_slots.resize(2 * n_nodes);
  for (int i = 0; i < n_nodes; ++i) {
    h.node_xy_slots[2 * i] = find_slot(h.matrix, 2 * i, 2 * i + 1);
    h.node_xy_slots[2 * i + 1] = find_slot(h.matrix, 2 * i + 1, 2 * i);
  }
  if (with_ceiling) {
    h.ceiling_dof = c;
    h.ceiling_slots.resize(2 * n_nodes);
    for (int i = 0; i < n_nodes; ++i) {
      h.ceiling_slots[2 * i] = find_slot(h.matrix, 2 * i + 1, c);
      h.ceiling_slots[2 * i + 1] = find_slot(h.matrix, c, 2 * i + 1);
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
