#include "core/sparse_hessian.h"

#include <algorithm>
#include <stdexcept>

namespace invfree {

namespace {
int find_slot(const Eigen::SparseMatrix<double>& m, int row, int col) {
  const int* inner = m.innerIndexPtr();
  const int begin = m.outerIndexPtr()[col], end = m.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(inner + begin, inner + end, row);
  if (it == inner + end || *it != row) throw std::logic_error("sparse pattern is missing an entry");
  return static_cast<int>(it - inner);
}
}  // namespace

SparseHessian build_sparse_hessian(const Mesh& mesh, bool with_ceiling) {
  const int n_nodes = mesh.node_count();
  const int n_dof = 2 * n_nodes + (with_ceiling ? 1 : 0);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(mesh.triangles.size() * 36 + n_dof + (with_ceiling ? 2 * n_nodes : 0));
  for (const auto& tri : mesh.triangles)
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b)
        entries.emplace_back(2 * tri[a / 2] + a % 2, 2 * tri[b / 2] + b % 2, 0.0);
  for (int i = 0; i < n_dof; ++i) entries.emplace_back(i, i, 0.0);
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
  if (with_ceiling) {
    h.ceiling_dof = c;
    h.ceiling_slots.resize(2 * n_nodes);
    for (int i = 0; i < n_nodes; ++i) {
      h.ceiling_slots[2 * i] = find_slot(h.matrix, 2 * i + 1, c);
      h.ceiling_slots[2 * i + 1] = find_slot(h.matrix, c, 2 * i + 1);
    }
  }
  h.set_zero();
  return h;
}

void SparseHessian::eliminate_ceiling() {
  if (ceiling_dof < 0) return;
  double* v = values();
  for (int s : ceiling_slots) v[s] = 0.0;
  v[diagonal_slots[ceiling_dof]] = 1.0;
}

}  // namespace invfree
