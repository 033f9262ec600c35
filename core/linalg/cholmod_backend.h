// The cholmod backend of LinearSolver (linear_solver.h): CHOLMOD's supernodal LL^T on a
// METIS ordering, refactorised for every solve, with CHOLMOD's memory served by a
// recycling pool and its BLAS on one thread (cholmod_backend.cpp says why). Also METIS's
// nested-dissection ordering through CHOLMOD's analysis, for the LDL^T backend.
//
// Built with INVFREE_NO_CHOLMOD (the web build, docs/web.md: SuiteSparse is not compiled
// to WebAssembly) every call reports failure, and LinearSolver uses its LDL^T instead.
#pragma once

#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "types.h"

namespace invfree {

class CholmodBackend {
 public:
  CholmodBackend();
  ~CholmodBackend();
  CholmodBackend(const CholmodBackend&) = delete;
  CholmodBackend& operator=(const CholmodBackend&) = delete;

  // Symbolic analysis of `pattern` (full symmetric storage; CHOLMOD reads its lower
  // triangle) and one warm-up factorisation and solve. False: CHOLMOD is not available or
  // the analysis failed.
  bool analyze(const Eigen::SparseMatrix<double>& pattern);
  // Numeric factorisation of `a` (the analysed pattern). False unless positive definite.
  bool factorize(const Eigen::SparseMatrix<double>& a);
  // x = A^-1 b with the last factorisation.
  bool solve(const VecX& b, VecX& x);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// METIS's nested-dissection ordering of `a` (postordered, through CHOLMOD's analysis) into
// new_to_old (sized a.rows()). False when METIS is unavailable or CHOLMOD chose another
// ordering; new_to_old is then unspecified.
bool metis_ordering(const Eigen::SparseMatrix<double>& a, std::vector<int>& new_to_old);

}  // namespace invfree
