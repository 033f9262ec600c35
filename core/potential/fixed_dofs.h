// Fixed nodes (Dirichlet boundary conditions, scene/fixed_nodes.h) eliminated from Newton's
// system as the tutorial's 2_dirichlet does and as the ceiling's fixed unknown is
// (CeilingPenalty::add_derivatives): their gradient entries are set to 0 and their rows
// and columns to those of the identity, so the direction is 0 there and the solve acts on
// the free degrees of freedom only. A fixed node then never moves: it starts at rest and
// every step's direction leaves it where it is.
// Inputs: the fixed nodes and the Hessian's pattern (slots precomputed once). Output: g and
// H modified in place.
#pragma once

#include <vector>

#include "linalg/sparse_hessian.h"

namespace invfree {

struct FixedDofs {
  bool on = false;
  std::vector<int> dofs;            // the held coordinates (2 node + 0 or 1), ascending
  std::vector<int> zero_slots;      // every entry in a fixed row or column, off its diagonal
  std::vector<int> diagonal_slots;  // the fixed dofs' diagonal entries
};

// dofs: scene/fixed_nodes.h's select_fixed_dofs (both coordinates of a node, or one).
inline FixedDofs make_fixed_dofs(const std::vector<int>& dofs, const SparseHessian& h) {
  FixedDofs f;
  f.on = !dofs.empty();
  const auto& m = h.matrix;
  for (int dof : dofs) {
    f.dofs.push_back(dof);
    f.diagonal_slots.push_back(h.diagonal_slots[dof]);
    for (int k = m.outerIndexPtr()[dof]; k < m.outerIndexPtr()[dof + 1]; ++k) {
      const int row = m.innerIndexPtr()[k];
      if (row == dof) continue;
      f.zero_slots.push_back(k);                         // (row, dof)
      f.zero_slots.push_back(sparse_slot(m, dof, row));  // (dof, row)
    }
  }
  return f;
}

inline void eliminate_fixed_dofs(const FixedDofs& f, double* g, double* hessian_values) {
  for (int dof : f.dofs) g[dof] = 0.0;
  for (int s : f.zero_slots) hessian_values[s] = 0.0;
  for (int s : f.diagonal_slots) hessian_values[s] = 1.0;
}

}  // namespace invfree
