// The block solve of PCG's correction (core/submatrix_ldlt.h): H_DD^-1 for sets shaped
// like the ones it gets (strips along a plane, scattered rows, the dense ceiling unknown,
// several components) to the accuracy of an independent factorisation, one object reused
// across sets; refuses sets and envelopes beyond its buffers and a submatrix that is not
// positive definite; keeps a strip's envelope narrow (that is what the ordering is for);
// takes the couplings a contact brings outside the matrix's pattern.
#include "linalg/submatrix_ldlt.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <random>

#include "tests/linalg/mesh_matrix.h"

namespace invfree {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

// H_DD x = b_D by Eigen's own LDL^T of the extracted submatrix.
VecX reference_solve(const SpMat& h, const std::vector<int>& set, const VecX& rhs) {
  const int m = static_cast<int>(set.size());
  std::vector<int> local(h.rows(), -1);
  for (int a = 0; a < m; ++a) local[set[a]] = a;
  std::vector<Eigen::Triplet<double>> t;
  for (int a = 0; a < m; ++a)
    for (SpMat::InnerIterator it(h, set[a]); it; ++it)
      if (local[it.row()] >= 0) t.emplace_back(local[it.row()], a, it.value());
  SpMat sub(m, m);
  sub.setFromTriplets(t.begin(), t.end());
  VecX b(m);
  for (int a = 0; a < m; ++a) b[a] = rhs[set[a]];
  Eigen::SimplicialLDLT<SpMat> ldlt(sub);
  return ldlt.solve(b);
}

// The unknowns of the nodes in rows [row0, row1] of the (n_seg + 1)^2 grid.
std::vector<int> strip(int n_seg, int row0, int row1) {
  std::vector<int> set;
  for (int r = row0; r <= row1; ++r)
    for (int c = 0; c <= n_seg; ++c) {
      const int node = r * (n_seg + 1) + c;
      set.push_back(2 * node);
      set.push_back(2 * node + 1);
    }
  return set;
}

TEST(SubmatrixLdlt, SolvesEveryKindOfSetOfTheNewtonSystem) {
  const int n_seg = 24;
  const SpMat h = mesh_matrix(n_seg, 0.1, 7);
  const int n = static_cast<int>(h.rows());
  const int ceiling = n - 1;
  std::mt19937 rng(11);
  std::vector<std::vector<int>> sets;
  sets.push_back(strip(n_seg, 0, 1));                          // contact strip
  std::vector<int> both = strip(n_seg, 0, 0);                  // two components and the
  for (int i : strip(n_seg, n_seg, n_seg)) both.push_back(i);  // ceiling, coupled to the
  both.push_back(ceiling);                                     // top row
  sets.push_back(both);
  std::vector<int> scattered;  // random rows, any order
  for (int i = n - 1; i >= 0; --i)
    if (rng() % 9 == 0) scattered.push_back(i);
  sets.push_back(scattered);
  sets.push_back({5});  // one unknown
  VecX rhs = VecX::Random(n);
  SubmatrixLdlt block;
  block.reserve(n, n, 64L * n);
  for (const auto& set : sets) {
    ASSERT_TRUE(block.factorize(h, set)) << set.size() << " unknowns";
    ASSERT_EQ(block.size(), static_cast<int>(set.size()));
    VecX x(n);
    block.solve(rhs, x);
    const VecX ref = reference_solve(h, set, rhs);
    EXPECT_LT((x.head(set.size()) - ref).norm(), 1e-12 * ref.norm()) << set.size() << " unknowns";
  }
}

// Couplings outside the pattern (linalg/node_coupling.h), as a fold's contacts bring them:
// nodes of the bottom row pressed against nodes three rows up, which share no triangle
// with them, one pair listed twice. The block solve sees h plus the couplings.
TEST(SubmatrixLdlt, SolvesWithCouplingsOutsideThePattern) {
  const int n_seg = 16;
  SpMat h = mesh_matrix(n_seg, 0.1, 9);
  const int n = static_cast<int>(h.rows());
  std::vector<NodeCoupling> couplings;
  SpMat merged = h;
  auto press = [&](int i, int j, const Vec2& normal, double k) {
    // k (e_i - e_j)(e_i - e_j)^T along the normal: PSD; its diagonal blocks go into the
    // pattern, its off-diagonal ones into the list, both orientations.
    const Mat2 nn = k * normal * normal.transpose();
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        h.coeffRef(2 * i + a, 2 * i + b) += nn(a, b);
        h.coeffRef(2 * j + a, 2 * j + b) += nn(a, b);
        merged.coeffRef(2 * i + a, 2 * i + b) += nn(a, b);
        merged.coeffRef(2 * j + a, 2 * j + b) += nn(a, b);
        merged.coeffRef(2 * i + a, 2 * j + b) -= nn(a, b);
        merged.coeffRef(2 * j + a, 2 * i + b) -= nn(a, b);
      }
    couplings.push_back({i, j, -nn});
    couplings.push_back({j, i, -nn});
  };
  const int row = n_seg + 1;
  for (int c = 2; c < 10; ++c) press(c, 3 * row + c + 1, Vec2(0.3, 1.0).normalized(), 40.0);
  press(4, 3 * row + 5, Vec2(0.0, 1.0), 25.0);  // the same pair again
  h.makeCompressed();
  merged.makeCompressed();
  ASSERT_EQ(h.nonZeros(), mesh_matrix(n_seg, 0.1, 9).nonZeros()) << "h keeps its pattern";
  std::vector<int> set = strip(n_seg, 0, 1);
  for (int i : strip(n_seg, 3, 4)) set.push_back(i);
  set.push_back(n - 1);  // the ceiling
  const VecX rhs = VecX::Random(n);
  SubmatrixLdlt block;
  block.reserve(n, n, 64L * n);
  ASSERT_TRUE(block.factorize(h, couplings, set));
  VecX x(n);
  block.solve(rhs, x);
  const VecX ref = reference_solve(merged, set, rhs);
  EXPECT_LT((x.head(set.size()) - ref).norm(), 1e-12 * ref.norm());
  // Without the couplings the block solves another matrix (the test can tell them apart).
  ASSERT_TRUE(block.factorize(h, set));
  block.solve(rhs, x);
  EXPECT_GT((x.head(set.size()) - ref).norm(), 1e-3 * ref.norm());
}

TEST(SubmatrixLdlt, KeepsAStripWithinANarrowBand) {
  // Two rows of nodes along the ground and the ceiling's unknown: the envelope of the
  // natural (row by row) order would hold ~ 2 (n_seg + 1) entries per row.
  const int n_seg = 64;
  const SpMat h = mesh_matrix(n_seg, 0.1, 3);
  std::vector<int> set = strip(n_seg, 0, 1);
  for (int i : strip(n_seg, n_seg, n_seg)) set.push_back(i);
  set.push_back(static_cast<int>(h.rows()) - 1);
  SubmatrixLdlt block;
  block.reserve(static_cast<int>(h.rows()), static_cast<int>(set.size()), 64L * set.size());
  ASSERT_TRUE(block.factorize(h, set));
  // The strips' rows: a few neighbours each; the ceiling's row: every unknown.
  EXPECT_LT(block.envelope(), 12L * static_cast<long>(set.size())) << block.envelope();
}

TEST(SubmatrixLdlt, RefusesWhatDoesNotFitOrIsNotPositiveDefinite) {
  const int n_seg = 16;
  SpMat h = mesh_matrix(n_seg, 0.1, 5);
  const int n = static_cast<int>(h.rows());
  const std::vector<int> set = strip(n_seg, 0, 2);
  SubmatrixLdlt block;
  block.reserve(n, static_cast<int>(set.size()) - 1, 64L * n);  // one unknown too few
  EXPECT_FALSE(block.factorize(h, set));
  EXPECT_EQ(block.size(), 0);
  block.reserve(n, n, 8);  // an envelope of 8 entries
  EXPECT_FALSE(block.factorize(h, set));
  block.reserve(n, n, 64L * n);
  EXPECT_TRUE(block.factorize(h, set));
  h.coeffRef(set[7], set[7]) = -1.0;  // not positive definite
  EXPECT_FALSE(block.factorize(h, set));
  EXPECT_EQ(block.size(), 0);
  const std::vector<int> other = strip(n_seg, 5, 6);  // still usable after a refusal
  EXPECT_TRUE(block.factorize(h, other));
}

}  // namespace
}  // namespace invfree
