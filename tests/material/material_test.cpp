// Every model: P against finite differences of Psi, dP/dF (unprojected) against finite
// differences of P, PSD projection properties, invariances, and the lecture's
// consistency conditions at F = I.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "material/models.h"
#include "tests/test_support.h"

namespace invfree {
namespace {

const Lame kLame = lame_from_young_poisson(1e5, 0.4);

struct ModelCase {
  Model model;
  bool rotation_invariant;
};
const ModelCase kModels[] = {{Model::NeoHookean, true},
                             {Model::Linear, false},
                             {Model::Arap, true},
                             {Model::StableNeoHookean, true}};

class MaterialTest : public ::testing::TestWithParam<ModelCase> {};

std::vector<Mat2> samples_for(Model m) {
  auto all = test::sample_deformation_gradients(model_allows_inversion(m), 300);
  if (m == Model::Arap) {  // the polar rotation is undefined where s1 + s2 = 0
    std::erase_if(all, [](const Mat2& F) {
      const PolarSvd s = polar_svd(F);
      return std::abs(s.sigma(0) + s.sigma(1)) < 0.05;
    });
  }
  return all;
}

double step_for(const Mat2& F) {
  const PolarSvd s = polar_svd(F);
  return 1e-6 * std::max(std::abs(s.sigma(1)), 1e-3);
}

TEST_P(MaterialTest, StressMatchesFiniteDifferenceOfEnergy) {
  const Model m = GetParam().model;
  for (const Mat2& F : samples_for(m)) {
    const std::function<double(const Vec4&)> psi = [&](const Vec4& f) {
      return energy_density(m, unflatten(f), kLame);
    };
    const Vec4 fd = test::fd_gradient(psi, flatten(F), step_for(F));
    const Vec4 P = flatten(first_piola(m, F, kLame));
    EXPECT_LT(test::relative_error(P, fd, kLame.mu), 1e-5) << model_name(m) << "\nF=\n" << F;
  }
}

TEST_P(MaterialTest, StressDerivativeMatchesFiniteDifferenceOfStress) {
  const Model m = GetParam().model;
  for (const Mat2& F : samples_for(m)) {
    const double eps = step_for(F);
    Mat4 fd;
    for (int k = 0; k < 4; ++k) {
      Vec4 a = flatten(F), b = a;
      a[k] += eps;
      b[k] -= eps;
      fd.col(k) = (flatten(first_piola(m, unflatten(a), kLame)) -
                   flatten(first_piola(m, unflatten(b), kLame))) /
                  (2 * eps);
    }
    const Mat4 exact = stress_derivative(m, F, kLame, false);
    EXPECT_LT(test::relative_error(exact, fd, kLame.mu), 1e-5) << model_name(m) << "\nF=\n" << F;
    EXPECT_LT((exact - exact.transpose()).norm(), 1e-9 * exact.norm());
  }
}

TEST_P(MaterialTest, ProjectedDerivativeIsPsdAndExactWherePsd) {
  const Model m = GetParam().model;
  int exact_psd_cases = 0, indefinite_cases = 0;
  for (const Mat2& F : samples_for(m)) {
    const Mat4 exact = stress_derivative(m, F, kLame, false);
    const Mat4 projected = stress_derivative(m, F, kLame, true);
    const double scale = exact.norm();
    Eigen::SelfAdjointEigenSolver<Mat4> eig_p(projected), eig_e(exact);
    EXPECT_GE(eig_p.eigenvalues().minCoeff(), -1e-10 * scale) << model_name(m) << "\n" << F;
    if (eig_e.eigenvalues().minCoeff() >= -1e-12 * scale) {
      ++exact_psd_cases;
      EXPECT_LT((projected - exact).norm(), 1e-10 * scale) << model_name(m) << "\n" << F;
    } else {
      ++indefinite_cases;
    }
  }
  EXPECT_GT(exact_psd_cases, 0);
  if (m != Model::Linear) {
    EXPECT_GT(indefinite_cases, 0) << "the sweep should reach indefinite states";
  }
}

TEST_P(MaterialTest, RotationAndIsotropyInvariance) {
  if (!GetParam().rotation_invariant) GTEST_SKIP() << "linear elasticity is not rotation invariant";
  const Model m = GetParam().model;
  for (const Mat2& F : samples_for(m)) {
    for (double a : {0.4, 2.0, -2.9}) {
      const double psi = energy_density(m, F, kLame);
      EXPECT_NEAR(energy_density(m, rotation(a) * F, kLame), psi,
                  1e-9 * std::max(1.0, std::abs(psi)));
      EXPECT_NEAR(energy_density(m, F * rotation(a), kLame), psi,
                  1e-9 * std::max(1.0, std::abs(psi)));
    }
  }
}

TEST_P(MaterialTest, RigidNullSpaceAndConsistencyAtRest) {
  const Model m = GetParam().model;
  // Psi(R) = 0 and P(R) = 0 for every rotation (linear elasticity: only R = I).
  for (double a : {0.0, 0.7, -2.0}) {
    if (!GetParam().rotation_invariant && a != 0.0) continue;
    EXPECT_NEAR(energy_density(m, rotation(a), kLame), 0.0, 1e-9 * kLame.mu);
    EXPECT_LT(first_piola(m, rotation(a), kLame).norm(), 1e-9 * kLame.mu);
  }
  // d2Psi/ds_i ds_j (I) = 2 mu d_ij + lambda: at F = I, dP/dF restricted to diagonal F.
  const Lame lame = m == Model::Arap ? Lame{kLame.mu, 0.0} : kLame;  // ARAP has no volume term
  const Mat4 d = stress_derivative(m, Mat2::Identity(), lame, false);
  EXPECT_NEAR(d(0, 0), 2 * lame.mu + lame.lambda, 1e-9 * lame.mu);
  EXPECT_NEAR(d(3, 3), 2 * lame.mu + lame.lambda, 1e-9 * lame.mu);
  EXPECT_NEAR(d(0, 3), lame.lambda, 1e-9 * lame.mu);
}

INSTANTIATE_TEST_SUITE_P(AllModels, MaterialTest, ::testing::ValuesIn(kModels),
                         [](const auto& info) {
                           std::string n = model_name(info.param.model);
                           std::erase(n, '-');
                           return n;
                         });

TEST(NeoHookean, DiagonalStressAgreesWithStressThroughSvd) {
  for (const Mat2& F : test::sample_deformation_gradients(false)) {
    const PolarSvd s = polar_svd(F);
    const Vec2 ps = NeoHookean::diagonal_stress(s.sigma, kLame);
    const Mat2 P = s.U * ps.asDiagonal() * s.V.transpose();
    EXPECT_LT((P - NeoHookean::first_piola(F, kLame)).norm(), 1e-9 * std::max(1.0, P.norm()));
  }
}

TEST(NeoHookean, FlipAndTwistMatchTheLectureQuotients) {
  // Away from s1 = s2 the closed forms must equal (Psi_1 -+ Psi_2)/(s1 -+ s2).
  for (Vec2 s : {Vec2(1.5, 0.7), Vec2(0.2, 0.05), Vec2(3.0, 1.0)}) {
    const Vec2 p = NeoHookean::diagonal_stress(s, kLame);
    const DiagonalHessian d = NeoHookean::diagonal_hessian(s, kLame);
    EXPECT_NEAR(d.flip, (p(0) - p(1)) / (s(0) - s(1)), 1e-8 * std::abs(d.flip));
    EXPECT_NEAR(d.twist, (p(0) + p(1)) / (s(0) + s(1)), 1e-8 * std::abs(d.twist));
  }
}

TEST(NeoHookean, InvertedIsInfinite) {
  EXPECT_TRUE(std::isinf(NeoHookean::energy_density(Vec2(1.0, -0.5).asDiagonal(), kLame)));
  EXPECT_TRUE(std::isinf(NeoHookean::energy_density(Mat2::Zero(), kLame)));
}

TEST(NeoHookean, SoftMaterialHessianIsNotTruncated) {
  // The reference Python code stored dP/dF in integer arrays, losing ~4% at E = 10.
  const Lame soft = lame_from_young_poisson(10.0, 0.4);
  const Mat2 F = Vec2(1.3, 0.8).asDiagonal();
  const Mat4 d = NeoHookean::stress_derivative(F, soft, false);
  const double eps = 1e-7;
  Vec4 a = flatten(F), b = a;
  a[0] += eps;
  b[0] -= eps;
  const Vec4 fd = (flatten(NeoHookean::first_piola(unflatten(a), soft)) -
                   flatten(NeoHookean::first_piola(unflatten(b), soft))) /
                  (2 * eps);
  EXPECT_LT((d.col(0) - fd).norm() / fd.norm(), 1e-7);
  EXPECT_NE(d(0, 0), std::trunc(d(0, 0)));
}

TEST(Lame, RoundTripsThroughYoungPoisson) {
  for (double nu : {0.0, 0.3, 0.49, 0.499}) {
    const Lame l = lame_from_young_poisson(1e5, nu);
    double E, n;
    young_poisson_from_lame(l, &E, &n);
    EXPECT_NEAR(E, 1e5, 1e-9 * 1e5);
    EXPECT_NEAR(n, nu, 1e-12);
  }
}

}  // namespace
}  // namespace invfree
