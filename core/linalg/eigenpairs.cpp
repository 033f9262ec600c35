#include "linalg/eigenpairs.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/MatOp/SymShiftInvert.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <algorithm>
#include <numeric>

namespace invfree {

EigenPairs smallest_eigenpairs(const SparseMatrixD& K, const SparseMatrixD* M, int count,
                               double shift, double tolerance) {
  EigenPairs out;
  const long n = K.rows();
  if (count < 1 || count >= n) {
    out.error = "asked for " + std::to_string(count) + " eigenpairs of a " + std::to_string(n) +
                "-unknown system (1 to " + std::to_string(n - 1) + ")";
    return out;
  }
  SparseMatrixD identity;
  if (!M) {
    identity.resize(n, n);
    identity.setIdentity();
  }
  const SparseMatrixD& B = M ? *M : identity;
  // One path for both problems: with M = I the generalized solver is the standard one.
  using ShiftInvert = Spectra::SymShiftInvert<double, Eigen::Sparse, Eigen::Sparse>;
  using MassProduct = Spectra::SparseSymMatProd<double>;
  ShiftInvert op(K, B);
  MassProduct mass(B);
  const int ncv = static_cast<int>(std::min<long>(n, std::max(2 * count + 1, count + 20)));
  Spectra::SymGEigsShiftSolver<ShiftInvert, MassProduct, Spectra::GEigsMode::ShiftInvert> solver(
      op, mass, count, ncv, shift);
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, 1000, tolerance);
  if (solver.info() != Spectra::CompInfo::Successful) {
    out.error = "the eigen-solver did not converge (Spectra, shift " + std::to_string(shift) + ")";
    return out;
  }
  const VecX values = solver.eigenvalues();
  const Eigen::MatrixXd vectors = solver.eigenvectors();
  std::vector<int> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return values[a] < values[b]; });
  out.values.resize(values.size());
  out.vectors.resize(n, values.size());
  for (size_t k = 0; k < order.size(); ++k) {
    out.values[k] = values[order[k]];
    out.vectors.col(k) = vectors.col(order[k]);
  }
  return out;
}

}  // namespace invfree
