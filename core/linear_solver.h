// Direct sparse solve of the Newton system H p = -g. The symbolic analysis (fill-reducing
// ordering and elimination tree) is done once per sparsity pattern; every Newton
// iteration only refactorises numerically.
#pragma once

#include <Eigen/SparseCholesky>
#include <memory>

#include "core/types.h"

namespace invfree {

class LinearSolver {
 public:
  void analyze(const Eigen::SparseMatrix<double>& pattern) {
    ldlt_ = std::make_unique<Ldlt>();
    ldlt_->analyzePattern(pattern);
  }
  bool analyzed() const { return ldlt_ != nullptr; }
  // Returns false when the factorisation breaks down (a zero pivot).
  bool factorize(const Eigen::SparseMatrix<double>& h) {
    ldlt_->factorize(h);
    return ldlt_->info() == Eigen::Success;
  }
  // Returns false when the solution is not finite.
  bool solve(const VecX& rhs, VecX& out) {
    out = ldlt_->solve(rhs);
    return ldlt_->info() == Eigen::Success && out.allFinite();
  }

 private:
  using Ldlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;
  std::unique_ptr<Ldlt> ldlt_;  // held by pointer: Eigen's solvers are not movable
};

}  // namespace invfree
