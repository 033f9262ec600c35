// The LDL^T backend's analysis (ldlt_backend.h): a fill-reducing ordering and the split
// of the elimination tree.
#include "linalg/ldlt_backend.h"

#include <algorithm>

#include <Eigen/OrderingMethods>
#include <vector>

#include "linalg/cholmod_backend.h"
#include "linalg/sparse_ldlt.h"

namespace invfree {

namespace {

using SpMat = Eigen::SparseMatrix<double>;

// new_to_old: METIS's nested dissection when asked for and available, else AMD.
std::vector<int> fill_reducing_ordering(const SpMat& a, bool nested_dissection) {
  const int n = static_cast<int>(a.rows());
  std::vector<int> new_to_old(n);
  if (!(nested_dissection && metis_ordering(a, new_to_old))) {
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm;
    Eigen::AMDOrdering<int> amd;
    amd(a, perm);
    for (int k = 0; k < n; ++k) new_to_old[k] = perm.indices()[k];
  }
  return new_to_old;
}

}  // namespace

void analyze_like_the_solver(const SpMat& pattern, SparseLdlt& ldlt) {
  ldlt.analyze(pattern,
               fill_reducing_ordering(pattern, pattern.rows() >= kNestedDissectionMinUnknowns),
               ldlt_parts(static_cast<int>(pattern.rows())));
}

int ldlt_parts(int unknowns) {
  if (unknowns < kParallelLdltMinUnknowns) return 1;
  return std::clamp(unknowns / kLdltUnknownsPerPart, 2, kLdltMaxParts);
}

}  // namespace invfree
