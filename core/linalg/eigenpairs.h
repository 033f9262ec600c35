// The smallest eigenpairs of a sparse symmetric matrix pencil, K phi = lambda M phi (M = I
// when none is given), by Spectra's shift-and-invert Lanczos (Debian's libspectra-dev):
// the eigenvalues nearest above `shift` are the largest of (K - shift M)^-1, which Lanczos
// finds in a few iterations. The shift must lie below the smallest eigenvalue wanted and
// must not be one (K - shift M is factorised by a sparse LDL^T): a stiffness matrix with
// rigid modes (eigenvalue 0) takes a small negative shift.
// Used by the modal reduced basis (scene/reduced_basis.h) and `invfree modes`.
#pragma once

#include <Eigen/Sparse>
#include <string>

#include "types.h"

namespace invfree {

using SparseMatrixD = Eigen::SparseMatrix<double>;

struct EigenPairs {
  VecX values;              // ascending
  Eigen::MatrixXd vectors;  // one column per value; M-orthonormal (orthonormal without M)
  std::string error;        // "" on success, otherwise why not (values and vectors empty)
};

// `count` pairs (1 <= count < K.rows()); K and M symmetric (both triangles stored), M
// positive definite. `tolerance`: Spectra's relative tolerance on the Ritz values.
EigenPairs smallest_eigenpairs(const SparseMatrixD& K, const SparseMatrixD* M, int count,
                               double shift, double tolerance = 1e-12);

}  // namespace invfree
