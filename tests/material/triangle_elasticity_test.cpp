// The per-triangle chain rule: 6-vector gradient and 6x6 Hessian against finite
// differences of the triangle's energy, for every model and projection mode.
#include "material/triangle_elasticity.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "material/models.h"
#include "scene/mesh.h"
#include "tests/test_support.h"

namespace invfree {
namespace {

const Lame kLame = lame_from_young_poisson(1e5, 0.4);

struct Triangle {
  Vec6 rest, x;
};

// A random rest triangle and a deformed placement x = F X + t with F from the sweep.
std::vector<Triangle> sample_triangles(Model m) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> out;
  for (const Mat2& F : test::sample_deformation_gradients(model_allows_inversion(m), 120)) {
    if (m == Model::Arap) {
      const PolarSvd s = polar_svd(F);
      if (std::abs(s.sigma(0) + s.sigma(1)) < 0.05) continue;
    }
    Triangle t;
    t.rest << 0, 0, 1 + 0.3 * u(rng), 0.2 * u(rng), 0.2 * u(rng), 1 + 0.3 * u(rng);
    const Vec2 shift(u(rng), u(rng));
    for (int a = 0; a < 3; ++a) t.x.segment<2>(2 * a) = F * t.rest.segment<2>(2 * a) + shift;
    out.push_back(t);
  }
  return out;
}

Mat2 rest_inverse(const Vec6& r) {
  Mat2 b;
  b.col(0) = r.segment<2>(2) - r.segment<2>(0);
  b.col(1) = r.segment<2>(4) - r.segment<2>(0);
  return b.inverse();
}

double rest_area(const Vec6& r) {
  Mat2 b;
  b.col(0) = r.segment<2>(2) - r.segment<2>(0);
  b.col(1) = r.segment<2>(4) - r.segment<2>(0);
  return 0.5 * b.determinant();
}

class TriangleTest : public ::testing::TestWithParam<Model> {};

TEST_P(TriangleTest, GradientAndHessianMatchFiniteDifferences) {
  const Model m = GetParam();
  visit_model(m, [&](auto model) {
    using M = decltype(model);
    for (const Triangle& t : sample_triangles(m)) {
      const Mat2 IB = rest_inverse(t.rest);
      const double area = rest_area(t.rest);
      const Mat46 dFdx = deformation_gradient_jacobian(IB);
      auto F_of = [&](const Vec6& x) {
        return deformation_gradient(x.segment<2>(0), x.segment<2>(2), x.segment<2>(4), IB);
      };
      const std::function<double(const Vec6&)> energy = [&](const Vec6& x) {
        return area * M::energy_density(F_of(x), kLame);
      };
      const PolarSvd s = polar_svd(F_of(t.x));
      const double eps = 1e-7 * std::max(std::abs(s.sigma(1)), 1e-3);
      const Vec6 g = TriangleElasticity<M>::gradient(F_of(t.x), dFdx, area, kLame);
      EXPECT_LT(test::relative_error(g, test::fd_gradient(energy, t.x, eps), kLame.mu), 1e-5);

      Mat6 fd;
      for (int k = 0; k < 6; ++k) {
        Vec6 a = t.x, b = t.x;
        a[k] += eps;
        b[k] -= eps;
        fd.col(k) = (TriangleElasticity<M>::gradient(F_of(a), dFdx, area, kLame) -
                     TriangleElasticity<M>::gradient(F_of(b), dFdx, area, kLame)) /
                    (2 * eps);
      }
      const Mat6 exact =
          TriangleElasticity<M>::hessian(F_of(t.x), dFdx, area, kLame, HessianProjection::None);
      EXPECT_LT(test::relative_error(exact, fd, kLame.mu), 1e-5) << model_name(m);

      for (auto proj : {HessianProjection::Diagonal, HessianProjection::Full}) {
        const Mat6 h = TriangleElasticity<M>::hessian(F_of(t.x), dFdx, area, kLame, proj);
        Eigen::SelfAdjointEigenSolver<Mat6> eig(h), eig_exact(exact);
        EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-9 * exact.norm()) << projection_name(proj);
        if (eig_exact.eigenvalues().minCoeff() >= 0.0) {
          EXPECT_LT((h - exact).norm(), 1e-9 * exact.norm()) << projection_name(proj);
        }
        // Translations stay in the null space whatever the projection.
        Vec6 shift;
        shift << 1, 0, 1, 0, 1, 0;
        EXPECT_LT((h * shift).norm(), 1e-8 * exact.norm());
      }
    }
  });
}

INSTANTIATE_TEST_SUITE_P(AllModels, TriangleTest,
                         ::testing::Values(Model::NeoHookean, Model::Linear, Model::Arap,
                                           Model::StableNeoHookean),
                         [](const auto& info) {
                           std::string n = model_name(info.param);
                           std::erase(n, '-');
                           return n;
                         });

}  // namespace
}  // namespace invfree
