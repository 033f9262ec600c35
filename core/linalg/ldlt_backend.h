// The ldlt backend of LinearSolver (linear_solver.h), which is also the factorisation PCG
// reuses: the project's own LDL^T (sparse_ldlt.h) analysed on a fill-reducing ordering,
// then factorised and solved by SparseLdlt itself.
//
// From kNestedDissectionMinUnknowns unknowns the ordering is METIS's nested dissection
// (through CHOLMOD's analysis, cholmod_backend.h): less fill than AMD on larger meshes and
// a balanced elimination tree for the threads; below it, and without CHOLMOD, AMD. From
// kParallelLdltMinUnknowns the tree's bottom is cut into ldlt_parts(n) bins below a top of
// chains (sparse_ldlt.h), which factorise and solve concurrently, level by level. The
// number of parts depends on the size alone, whatever the thread count, so results are
// bit-identical on any machine.
#pragma once

#include <Eigen/SparseCore>

namespace invfree {

class SparseLdlt;

constexpr int kNestedDissectionMinUnknowns = 5000;
constexpr int kParallelLdltMinUnknowns = 1000;
// About one part per kLdltUnknownsPerPart unknowns, at most kLdltMaxParts: enough
// subtrees to keep 16 threads busy at n_seg 128 and above, few enough that a level's
// fork-join and the accumulators cost little next to the work on smaller meshes.
constexpr int kLdltUnknownsPerPart = 1000;
constexpr int kLdltMaxParts = 64;
int ldlt_parts(int unknowns);

// The analysis of `pattern` (full symmetric storage) exactly as the solver makes it
// (ordering and parts above); also for benchmarks and tests that time a SparseLdlt of
// their own.
void analyze_like_the_solver(const Eigen::SparseMatrix<double>& pattern, SparseLdlt& ldlt);

}  // namespace invfree
