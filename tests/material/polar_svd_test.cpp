#include "material/polar_svd.h"

#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace invfree {
namespace {

TEST(PolarSvd, ReconstructsWithRotationsAndSignedSigma) {
  for (const Mat2& F : test::sample_deformation_gradients(true, 500)) {
    const PolarSvd s = polar_svd(F);
    EXPECT_NEAR(s.U.determinant(), 1.0, 1e-14);
    EXPECT_NEAR(s.V.determinant(), 1.0, 1e-14);
    EXPECT_LT((s.U.transpose() * s.U - Mat2::Identity()).norm(), 1e-14);
    const Mat2 back = s.U * s.sigma.asDiagonal() * s.V.transpose();
    EXPECT_LT((back - F).norm(), 1e-13 * F.norm()) << F;
    EXPECT_GE(s.sigma(0), std::abs(s.sigma(1)) * (1 - 1e-12));
    EXPECT_EQ(s.sigma(1) < 0, F.determinant() < 0);
  }
}

TEST(PolarSvd, SmallSingularValueKeepsRelativeAccuracy) {
  // F = diag(1, tiny) rotated: q - r would lose every digit of sigma_2. The reference is
  // the stored F's own determinant in extended precision over sigma_1 (the rounded
  // entries of F define its true sigma_2, not `tiny`).
  for (double tiny : {1e-6, 1e-9, 1e-12}) {
    const Mat2 F = rotation(0.3) * Vec2(1.0, tiny).asDiagonal() * rotation(-1.1);
    const PolarSvd s = polar_svd(F);
    const long double det = (long double)F(0, 0) * F(1, 1) - (long double)F(0, 1) * F(1, 0);
    const double reference = static_cast<double>(det / s.sigma(0));
    EXPECT_NEAR(s.sigma(1) / reference, 1.0, 1e-6) << tiny;
    EXPECT_NEAR(s.sigma(1) / tiny, 1.0, 1e-3) << tiny;
  }
}

TEST(PolarSvd, ReflectionGivesNegativeSecondValue) {
  const Mat2 F = Vec2(2.0, -0.5).asDiagonal();
  const PolarSvd s = polar_svd(F);
  EXPECT_NEAR(s.sigma(0), 2.0, 1e-15);
  EXPECT_NEAR(s.sigma(1), -0.5, 1e-15);
}

TEST(PolarSvd, ZeroMatrix) {
  const PolarSvd s = polar_svd(Mat2::Zero());
  EXPECT_EQ(s.sigma(0), 0.0);
  EXPECT_EQ(s.sigma(1), 0.0);
  EXPECT_TRUE(s.U.allFinite() && s.V.allFinite());
}

}  // namespace
}  // namespace invfree
