// The project's LDL^T (core/sparse_ldlt.h): it solves SPD and indefinite systems to the
// accuracy of an independent factorisation, refuses what it must, cuts the elimination
// tree into independent parts that really are independent, and gives the same bits for
// any number of threads.
#include "linalg/sparse_ldlt.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <algorithm>
#include <Eigen/SparseCholesky>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>

#include "linalg/ldlt_backend.h"
#include "linalg/parallel.h"
#include "linalg/sparse_hessian.h"
#include "scene/mesh.h"
#include "tests/linalg/mesh_matrix.h"

namespace invfree {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

std::vector<int> amd_order(const SpMat& a) {
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm;
  Eigen::AMDOrdering<int> amd;
  amd(a, perm);
  return std::vector<int>(perm.indices().data(), perm.indices().data() + a.rows());
}

TEST(SparseLdlt, SolvesLikeAnIndependentFactorisation) {
  for (int n_seg : {1, 3, 12, 40}) {
    const SpMat a = mesh_matrix(n_seg, 1.0, 7u + n_seg);
    const VecX b = VecX::LinSpaced(a.rows(), -1.0, 2.0);
    const VecX exact = Eigen::SimplicialLDLT<SpMat>(a).solve(b);
    for (int parts : {1, 2, 3, 16, 64}) {
      SparseLdlt ldlt;
      ldlt.analyze(a, amd_order(a), parts);
      ASSERT_TRUE(ldlt.factorize(a)) << n_seg << " " << parts;
      VecX x(a.rows());
      ldlt.solve(b, x);
      EXPECT_LT((x - exact).norm(), 1e-12 * exact.norm())
          << "n_seg " << n_seg << ", parts " << parts;
      EXPECT_LT((a * x - b).norm(), 1e-12 * b.norm());
      if (parts == 1) {
        EXPECT_EQ(ldlt.serial_fraction(), 0.0);
        EXPECT_EQ(ldlt.task_count(), 1);
      }
      EXPECT_LT(ldlt.serial_fraction(), 0.5);
    }
  }
}

TEST(SparseLdlt, SolvesSupernodesOfEveryWidth) {
  // The forward solve works on blocks of up to four columns of a supernode: a dense
  // matrix is one supernode as wide as it is (every block width and remainder), and the
  // solver's own nested-dissection ordering of a larger mesh has wide separators above
  // sparse rows.
  std::mt19937 rng(11u);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int size = 1; size <= 11; ++size) {
    Eigen::MatrixXd m(size, size);
    for (int i = 0; i < size; ++i)
      for (int j = 0; j <= i; ++j) m(i, j) = m(j, i) = u(rng);
    m += (size + 1.0) * Eigen::MatrixXd::Identity(size, size);
    const SpMat a = m.sparseView();
    const VecX b = VecX::LinSpaced(size, -1.0, 2.0);
    const VecX exact = m.ldlt().solve(b);
    std::vector<int> order(size);
    std::iota(order.begin(), order.end(), 0);
    SparseLdlt ldlt;
    ldlt.analyze(a, order, 2);
    ASSERT_TRUE(ldlt.factorize(a));
    VecX x(size);
    ldlt.solve(b, x);
    EXPECT_LT((x - exact).norm(), 1e-13 * exact.norm()) << "dense, size " << size;
  }
  const SpMat a = mesh_matrix(52, 1.0, 12u);
  ASSERT_GE(a.rows(), kNestedDissectionMinUnknowns);
  const VecX b = VecX::LinSpaced(a.rows(), -1.0, 2.0);
  const VecX exact = Eigen::SimplicialLDLT<SpMat>(a).solve(b);
  SparseLdlt ldlt;
  analyze_like_the_solver(a, ldlt);
  ASSERT_TRUE(ldlt.factorize(a));
  VecX x(a.rows());
  ldlt.solve(b, x);
  EXPECT_LT((x - exact).norm(), 1e-12 * exact.norm());
  EXPECT_LT((a * x - b).norm(), 1e-12 * b.norm());
}

// Dense leaf blocks of widths 1 to 13 (each a supernode), every one coupled to some rows of
// two separators above it (rows below in the same task and in others, by `parts`): the
// dense solve's triangle, its rows below, the split and the accumulator slots.
SpMat block_tree_matrix(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<int> widths;
  for (int w = 1; w <= 13; ++w) widths.push_back(w);
  std::shuffle(widths.begin(), widths.end(), rng);
  int leaves = 0;
  for (int w : widths) leaves += w;
  const int mid = 11, top = 7, n = leaves + 2 * mid + top;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  int first = 0;
  for (std::size_t b = 0; b < widths.size(); ++b) {
    const int sep = leaves + (b < widths.size() / 2 ? 0 : mid);
    for (int i = first; i < first + widths[b]; ++i) {
      for (int j = first; j < i; ++j) m(i, j) = u(rng);
      for (int j = sep; j < sep + mid; ++j)
        if (u(rng) > -0.3) m(j, i) = u(rng);
      for (int j = leaves + 2 * mid; j < n; ++j)
        if (u(rng) > 0.4) m(j, i) = u(rng);
    }
    first += widths[b];
  }
  for (int i = leaves; i < n; ++i)
    for (int j = leaves; j < i; ++j) m(i, j) = u(rng);
  m = m.triangularView<Eigen::StrictlyLower>();
  m = m + m.transpose().eval();
  for (int i = 0; i < n; ++i) m(i, i) = m.row(i).cwiseAbs().sum() + 1.0;
  return m.sparseView();
}

TEST(SparseLdlt, DenseSupernodesSolveLikeADenseReference) {
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    const SpMat a = block_tree_matrix(seed);
    const Eigen::MatrixXd dense(a);
    const VecX b = VecX::LinSpaced(a.rows(), -1.0, 2.0);
    const VecX exact = dense.ldlt().solve(b);
    std::vector<int> order(a.rows());
    std::iota(order.begin(), order.end(), 0);
    for (int parts : {1, 2, 3, 5, 16}) {
      std::vector<VecX> results;
      for (int threads : {1, 2, 3}) {
        set_thread_count(threads);
        SparseLdlt ldlt;
        ldlt.analyze(a, order, parts);
        ASSERT_TRUE(ldlt.factorize(a));
        VecX x(a.rows());
        ldlt.solve(b, x);
        EXPECT_LT((x - exact).norm(), 1e-12 * exact.norm()) << seed << " parts " << parts;
        ldlt.keep_float_copy(true);
        ASSERT_TRUE(ldlt.factorize(a));
        VecX xf(a.rows());
        ldlt.solve_float(b, xf);
        EXPECT_LT((xf - exact).norm(), 1e-5 * exact.norm()) << seed << " parts " << parts;
        results.push_back(x);
      }
      for (std::size_t k = 1; k < results.size(); ++k)
        EXPECT_EQ(0, std::memcmp(results[0].data(), results[k].data(),
                                 sizeof(double) * results[0].size()))
            << "seed " << seed << ", parts " << parts << ": threads differ";
    }
  }
  set_thread_count(0);
}

TEST(SparseLdlt, RefactorisesNewValuesOnTheSamePattern) {
  // A second factorisation must not see anything of the first (row marks, counts).
  const SpMat a = mesh_matrix(24, 1.0, 1u), c = mesh_matrix(24, 3.0, 2u);
  SparseLdlt ldlt;
  ldlt.analyze(a, amd_order(a), 2);
  const VecX b = VecX::Ones(a.rows());
  VecX x(a.rows());
  for (const SpMat* m : {&a, &c, &a}) {
    ASSERT_TRUE(ldlt.factorize(*m));
    ldlt.solve(b, x);
    EXPECT_LT((*m * x - b).norm(), 1e-12 * b.norm());
  }
}

TEST(SparseLdlt, IndefiniteOnlyWhenAllowed) {
  const SpMat a = mesh_matrix(16, -1.0, 3u);
  const VecX b = VecX::LinSpaced(a.rows(), 1.0, -1.0);
  SparseLdlt ldlt;
  ldlt.analyze(a, amd_order(a), 2);
  EXPECT_FALSE(ldlt.factorize(a, true));  // a negative pivot: not positive definite
  ASSERT_TRUE(ldlt.factorize(a, false));
  VecX x(a.rows());
  ldlt.solve(b, x);
  EXPECT_LT((a * x - b).norm(), 1e-10 * b.norm());
}

TEST(SparseLdlt, RefusesNonFiniteValues) {
  SpMat a = mesh_matrix(16, 1.0, 4u);
  SparseLdlt ldlt;
  ldlt.analyze(a, amd_order(a), 2);
  a.coeffRef(5, 5) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(ldlt.factorize(a, true));
  EXPECT_FALSE(ldlt.factorize(a, false));
}

TEST(SparseLdlt, TwoBinsRunConcurrentlyOnMostOfTheWork) {
  // The point of the split: on a mesh the top of the tree is a small part of the solve.
  const SpMat a = mesh_matrix(64, 1.0, 5u);
  SparseLdlt ldlt;
  ldlt.analyze(a, amd_order(a), 2);
  EXPECT_GT(ldlt.serial_fraction(), 0.0);
  EXPECT_LT(ldlt.serial_fraction(), 0.2);
  EXPECT_GT(ldlt.schedule_speedup(2), 1.6);
}

TEST(SparseLdlt, ManyPartsLetManyThreadsWork) {
  // The levels above the bins run the top's chains side by side, so the schedule's
  // speed-up goes on growing with the threads, up to the tree's work / span.
  const SpMat a = mesh_matrix(96, 1.0, 5u);
  SparseLdlt ldlt;
  analyze_like_the_solver(a, ldlt);
  ASSERT_GT(ldlt.task_count(), ldlt_parts(static_cast<int>(a.rows())));  // bins and chains
  const SparseLdlt::TreeParallelism tree = ldlt.tree_parallelism();
  const double s2 = ldlt.schedule_speedup(2), s16 = ldlt.schedule_speedup(16);
  EXPECT_GT(s2, 1.8);
  EXPECT_GT(s16, 5.0);
  EXPECT_LE(s16, tree.solve_work / tree.solve_span * 1.0001);
  EXPECT_LT(tree.factor_work / tree.factor_span, tree.solve_work / tree.solve_span);
  EXPECT_GT(tree.factor_work / tree.factor_span, 1.0);
}

TEST(SparseLdlt, PartsSolveAlikeAndThreadsBitForBit) {
  // The parts fix the order of the forward solve's sums: different parts agree to
  // rounding, and for given parts every thread count gives the same bits.
  const SpMat a = mesh_matrix(48, 1.0, 12u);
  const VecX b = VecX::LinSpaced(a.rows(), -2.0, 5.0);
  VecX reference(a.rows());
  for (int parts : {1, 9, 64}) {
    std::vector<VecX> results;
    for (int threads : {1, 2, 4, 7}) {
      set_thread_count(threads);
      SparseLdlt ldlt;
      ldlt.analyze(a, amd_order(a), parts);
      ASSERT_TRUE(ldlt.factorize(a));
      VecX x(a.rows());
      ldlt.solve(b, x);
      results.push_back(x);
    }
    if (parts == 1) reference = results[0];
    EXPECT_LT((results[0] - reference).norm(), 1e-13 * reference.norm()) << parts;
    for (std::size_t k = 1; k < results.size(); ++k)
      EXPECT_EQ(0, std::memcmp(results[0].data(), results[k].data(),
                               sizeof(double) * results[0].size()))
          << "parts " << parts << ": threads differ";
  }
  set_thread_count(0);
}

TEST(SparseLdlt, SolvesReadOneRowListPerSupernode) {
  // Two unknowns per node: nearly every column shares its rows with the next one, so the
  // solves read well under half as many indices as L has entries (the accuracy of what
  // they compute is checked above).
  const SpMat a = mesh_matrix(40, 1.0, 8u);
  SparseLdlt ldlt;
  ldlt.analyze(a, amd_order(a), 2);
  EXPECT_GT(ldlt.solve_row_indices(), 0);
  EXPECT_LT(ldlt.solve_row_indices(), ldlt.factor_nonzeros() / 2);
}

TEST(SparseLdlt, FloatCopySolvesToSinglePrecisionAndOnlyWhenKept) {
  const SpMat a = mesh_matrix(24, 1.0, 9u);
  const VecX b = VecX::LinSpaced(a.rows(), -1.0, 1.0);
  SparseLdlt ldlt;
  ldlt.analyze(a, amd_order(a), 2);
  ASSERT_TRUE(ldlt.factorize(a));
  VecX exact(a.rows()), x(a.rows());
  ldlt.solve(b, exact);
  ldlt.solve_float(b, x);  // no copy kept: the double solve, bit for bit
  EXPECT_EQ(0, std::memcmp(x.data(), exact.data(), sizeof(double) * x.size()));
  ldlt.keep_float_copy(true);
  ASSERT_TRUE(ldlt.factorize(a));  // the copy is made by the factorisation
  ldlt.solve_float(b, x);
  const double error = (x - exact).norm() / exact.norm();
  EXPECT_GT(error, 0.0);   // it really read the rounded values
  EXPECT_LT(error, 1e-5);  // float's 6e-8 per entry, times this matrix's small condition
  ldlt.solve(b, x);        // the double values are still there
  EXPECT_EQ(0, std::memcmp(x.data(), exact.data(), sizeof(double) * x.size()));
}

TEST(SparseLdlt, BlockedFactorisationHasTheColumnLoopsBits) {
  // Supernode blocks of every width, partial supernodes (rows inside a supernode) and
  // split runs: a mesh with two unknowns per node under METIS, a jittered one under AMD,
  // and a dense matrix.
  std::mt19937 rng(3u);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd dense = Eigen::MatrixXd::NullaryExpr(23, 23, [&] { return u(rng); });
  dense = dense * dense.transpose() + 23.0 * Eigen::MatrixXd::Identity(23, 23);
  const std::vector<SpMat> matrices = {mesh_matrix(40, 1.0, 6u), mesh_matrix(17, 1.0, 2u),
                                       dense.sparseView()};
  for (const SpMat& a : matrices) {
    const VecX b = VecX::LinSpaced(a.rows(), -3.0, 1.0);
    VecX x[2];
    for (int blocked : {0, 1}) {
      SparseLdlt ldlt;
      analyze_like_the_solver(a, ldlt);
      ldlt.set_factor_method(blocked != 0 ? SparseLdlt::FactorMethod::kRows
                                            : SparseLdlt::FactorMethod::kRowsOneColumnAtATime);
      ASSERT_TRUE(ldlt.factorize(a));
      x[blocked].resize(a.rows());
      ldlt.solve(b, x[blocked]);
    }
    EXPECT_LT((a * x[1] - b).norm(), 1e-12 * b.norm());
    EXPECT_EQ(0, std::memcmp(x[0].data(), x[1].data(), sizeof(double) * x[0].size()))
        << a.rows() << " unknowns";
  }
}

// The supernodal factorisation (the default) against a dense LDL^T: dense leaf blocks of
// widths 1 to 13 under two separators, the solver's METIS ordering of a mesh (separators
// wider than a panel of 32 columns: the panels' products and the descendants' blocked
// updates), and a dense matrix of 75 columns (one supernode, three panels). The matrices
// are diagonally dominant or mesh Laplacians of condition below ~1e4, so a backward-stable
// factor solves to ~1e-16 x 1e4; 1e-12 leaves room and still sees any missing update.
TEST(SparseLdlt, SupernodalFactorSolvesLikeADenseReference) {
  std::mt19937 rng(5u);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd dense = Eigen::MatrixXd::NullaryExpr(75, 75, [&] { return u(rng); });
  dense = dense * dense.transpose() + 75.0 * Eigen::MatrixXd::Identity(75, 75);
  // One supernode of 301 columns: ten panels, each updating every column to its right, the
  // last one shorter than the others.
  Eigen::MatrixXd wide = Eigen::MatrixXd::NullaryExpr(301, 301, [&] { return u(rng); });
  wide = wide * wide.transpose() + 301.0 * Eigen::MatrixXd::Identity(301, 301);
  // n_seg 100: a top separator of ~200 columns, updated by hundreds of descendants.
  std::vector<SpMat> matrices = {block_tree_matrix(1u),     block_tree_matrix(2u),
                                 mesh_matrix(52, 1.0, 12u), dense.sparseView(),
                                 wide.sparseView(),         mesh_matrix(100, 1.0, 13u)};
  for (const SpMat& a : matrices) {
    const bool large = a.rows() >= kNestedDissectionMinUnknowns;
    const VecX b = VecX::LinSpaced(a.rows(), -1.0, 2.0);
    const VecX exact = large ? VecX(Eigen::SimplicialLDLT<SpMat>(a).solve(b))
                             : VecX(Eigen::MatrixXd(a).ldlt().solve(b));
    std::vector<int> order(a.rows());
    std::iota(order.begin(), order.end(), 0);
    for (int parts : {1, 2, 5, 16}) {
      std::vector<VecX> results;
      for (int threads : {1, 2, 3}) {
        set_thread_count(threads);
        SparseLdlt ldlt;
        if (large)
          analyze_like_the_solver(a, ldlt);
        else
          ldlt.analyze(a, order, parts);
        ASSERT_TRUE(ldlt.factorize(a));
        VecX x(a.rows());
        ldlt.solve(b, x);
        EXPECT_LT((x - exact).norm(), 1e-12 * exact.norm())
            << a.rows() << " unknowns, parts " << parts << ", threads " << threads;
        EXPECT_LT((a * x - b).norm(), 1e-12 * b.norm());
        // The rows' factor (up-looking, other rounding) solves the same way.
        SparseLdlt rows;
        rows.set_factor_method(SparseLdlt::FactorMethod::kRows);
        if (large)
          analyze_like_the_solver(a, rows);
        else
          rows.analyze(a, order, parts);
        ASSERT_TRUE(rows.factorize(a));
        VecX y(a.rows());
        rows.solve(b, y);
        EXPECT_LT((x - y).norm(), 1e-12 * y.norm());
        results.push_back(x);
      }
      for (std::size_t k = 1; k < results.size(); ++k)
        EXPECT_EQ(0, std::memcmp(results[0].data(), results[k].data(),
                                 sizeof(double) * results[0].size()))
            << a.rows() << " unknowns, parts " << parts << ": threads differ";
      if (large) break;  // the solver's own part count
    }
  }
  set_thread_count(0);
}

// Symmetric indefinite matrices whose leading minors are all nonzero: dense supernodes of
// 70 columns (three panels) and 260 (nine panels, one front) and a mesh with a negative
// diagonal shift. Without positive_definite they factorise and solve like a dense
// reference; with it the first negative pivot is reported as a failure.
TEST(SparseLdlt, SupernodalFactorTakesIndefiniteMatricesOnlyWhenAllowed) {
  std::mt19937 rng(7u);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto indefinite = [&](int n) {
    Eigen::MatrixXd m = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return u(rng); });
    m = (m + m.transpose()).eval();
    for (int i = 0; i < n; ++i) m(i, i) = (i % 3 == 1 ? -1.0 : 1.0) * (3.0 * n / 7.0 + i);
    return SpMat(m.sparseView());
  };
  const std::vector<SpMat> matrices = {indefinite(70), indefinite(260), mesh_matrix(30, -1.0, 3u)};
  for (const SpMat& a : matrices) {
    const VecX b = VecX::LinSpaced(a.rows(), 1.0, -1.0);
    const VecX exact = Eigen::SimplicialLDLT<SpMat>(a).solve(b);
    std::vector<int> order(a.rows());
    std::iota(order.begin(), order.end(), 0);
    SparseLdlt ldlt;
    const bool dense = a.rows() == 70 || a.rows() == 260;
    ldlt.analyze(a, dense ? order : amd_order(a), a.rows() == 260 ? 1 : 3);
    EXPECT_FALSE(ldlt.factorize(a, true)) << a.rows();
    ASSERT_TRUE(ldlt.factorize(a, false)) << a.rows();
    VecX x(a.rows());
    ldlt.solve(b, x);
    EXPECT_LT((x - exact).norm(), 1e-10 * exact.norm()) << a.rows();
    EXPECT_LT((a * x - b).norm(), 1e-10 * b.norm()) << a.rows();
  }
  // A zero pivot is refused either way: [[1, 1], [1, 1]] in any supernode.
  Eigen::MatrixXd singular = Eigen::MatrixXd::Identity(40, 40);
  singular.block(10, 10, 2, 2).setOnes();
  const SpMat s = singular.sparseView();
  std::vector<int> order(40);
  std::iota(order.begin(), order.end(), 0);
  SparseLdlt ldlt;
  ldlt.analyze(s, order, 1);
  EXPECT_FALSE(ldlt.factorize(s, false));
  EXPECT_FALSE(ldlt.factorize(s, true));
}

TEST(SparseLdlt, BitIdenticalForAnyThreadCount) {
  const SpMat a = mesh_matrix(40, 1.0, 6u);
  const VecX b = VecX::LinSpaced(a.rows(), -3.0, 1.0);
  std::vector<VecX> results;
  for (int threads : {1, 2, 3}) {
    set_thread_count(threads);
    SparseLdlt ldlt;
    analyze_like_the_solver(a, ldlt);
    ASSERT_TRUE(ldlt.factorize(a));
    VecX x(a.rows());
    for (int repeat = 0; repeat < 3; ++repeat) ldlt.solve(b, x);
    results.push_back(x);
  }
  set_thread_count(0);
  for (std::size_t k = 1; k < results.size(); ++k)
    EXPECT_EQ(0,
              std::memcmp(results[0].data(), results[k].data(), sizeof(double) * results[0].size()))
        << "threads differ";
}

}  // namespace
}  // namespace invfree
