// A symmetric sparse matrix (both triangles stored, column-major CSC) whose pattern is
// fixed for a mesh, with precomputed positions ("slots") into its value array so that
// assembly is a scatter with no search and no allocation. Inputs: the mesh and whether a
// ceiling degree of freedom follows the 2N node coordinates. Pattern: every node pair
// that shares a triangle, the diagonal, and the ceiling's coupling to every node's y.
// It also carries the parallel assembly plan: triangles in chunks of consecutive indices,
// the chunks grouped into colours so that no two chunks of one colour share a node. The
// chunks of a colour scatter concurrently without locks, and every slot receives its
// contributions in an order fixed by the mesh alone (colour, chunk, triangle), so the sum
// is bit-identical whatever the number of threads.
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <span>
#include <vector>

#include "linalg/node_coupling.h"
#include "scene/mesh.h"

namespace invfree {

struct SparseHessian {
  Eigen::SparseMatrix<double> matrix;
  std::vector<int> triangle_slots;  // 36 per triangle, row-major over the local 6x6
  std::vector<int> diagonal_slots;  // one per degree of freedom
  std::vector<int> ceiling_slots;   // per node: (y_i, c) then (c, y_i)
  std::vector<int> node_xy_slots;   // per node: (x_i, y_i) then (y_i, x_i)
  int ceiling_dof = -1;             // -1 when the scene has no ceiling
  // Assembly plan. Colour c owns chunks chunk_order[colour_begin[c] .. colour_begin[c+1]);
  // chunk k holds triangles [k * chunk_size, min((k + 1) * chunk_size, triangle count)).
  int chunk_size = 128;
  std::vector<int> colour_begin;
  std::vector<int> chunk_order;
  int colour_count() const { return static_cast<int>(colour_begin.size()) - 1; }
  // Node pairs (i < j, sorted) coupled beyond the mesh's triangles: contact blocks that come
  // and go (potential/self_contact.h). The pattern holds both (i, j) and (j, i) 2x2 blocks.
  // pattern_version changes whenever the pattern is rebuilt, so the linear solver knows
  // to redo its symbolic analysis.
  std::vector<std::array<int, 2>> extra_pairs;
  int pattern_version = 0;
  // Contact blocks outside the pattern, without a rebuild. With keep_couplings (Newton sets
  // it where PCG solves the system: linear_solver.h's solves_by_pcg), add_node_block keeps
  // the 2x2 block of a node pair the pattern lacks in `couplings` (linalg/node_coupling.h)
  // instead of the pattern growing; the matrix is then `matrix` plus the couplings, and the
  // PCG solve multiplies them and corrects its factor, which never holds them, on their
  // nodes (pcg.h). Without it (the direct solvers, a reduced basis) such a block makes the
  // assembly rebuild the pattern (incremental_potential.h) and the solver redo its
  // analysis. Cleared by every assembly.
  bool keep_couplings = false;
  std::vector<NodeCoupling> couplings;

  void set_zero() {
    std::fill_n(matrix.valuePtr(), matrix.nonZeros(), 0.0);
    couplings.clear();
  }
  double* values() { return matrix.valuePtr(); }
};

// extra_pairs: node pairs coupled by a term beyond the triangles (the mass-spring
// potential's second diagonals); their 2x2 blocks join the pattern.
SparseHessian build_sparse_hessian(const Mesh& mesh, bool with_ceiling,
                                   std::span<const std::array<int, 2>> extra_pairs = {});
// The position of entry (row, col) in the matrix's value array; throws when the pattern
// has no such entry.
int sparse_slot(const Eigen::SparseMatrix<double>& m, int row, int col);

// True when add_node_block can take the 2x2 block of nodes (i, j): the pattern holds it
// (both triangles), or the Hessian keeps blocks outside its pattern (keep_couplings).
bool has_node_block(const SparseHessian& h, int i, int j);
// True when the pattern itself holds the 2x2 block of nodes (i, j).
bool pattern_has_node_block(const SparseHessian& h, int i, int j);
// Adds a 2x2 block at nodes (i, j): into the pattern, or (keep_couplings) as a coupling
// when the pattern lacks it (a zero block is dropped); otherwise the pattern must hold it.
void add_node_block(SparseHessian& h, int i, int j, const Mat2& block);
// y = H v, the couplings included (Eigen's product plus add_couplings_product).
void multiply_hessian(const SparseHessian& h, const VecX& v, VecX& y);

}  // namespace invfree
