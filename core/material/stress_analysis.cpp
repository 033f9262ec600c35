#include "material/stress_analysis.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "material/models.h"

namespace invfree {

namespace {

// Eigen-decomposition of a symmetric 2x2 matrix in closed form: values larger first, unit
// vectors as columns in that order.
void symmetric_eigen(const Mat2& a, Vec2* values, Mat2* vectors) {
  const double mean = 0.5 * (a(0, 0) + a(1, 1));
  const double half_diff = 0.5 * (a(0, 0) - a(1, 1));
  const double off = 0.5 * (a(0, 1) + a(1, 0));
  const double radius = std::hypot(half_diff, off);
  *values = Vec2(mean + radius, mean - radius);
  if (!vectors) return;
  // The larger eigenvalue's vector at angle theta/2 with tan(theta) = off / half_diff.
  const double theta = 0.5 * std::atan2(off, half_diff);
  const double c = std::cos(theta), s = std::sin(theta);
  *vectors << c, -s, s, c;
}

template <class M>
constexpr bool kHasDiagonalSpace = requires(const Vec2& s, const Lame& l) {
  M::diagonal_hessian(s, l);
};

// The four eigenvalues of dP/dF in kEigenvalueNames' order.
template <class M>
Vec4 stress_derivative_eigenvalues(const Vec2& sigma, const Lame& l) {
  if constexpr (kHasDiagonalSpace<M>) {
    const DiagonalHessian d = M::diagonal_hessian(sigma, l);
    Vec2 a;
    symmetric_eigen(d.A, &a, nullptr);
    return Vec4(a(0), a(1), d.flip, d.twist);
  } else {
    // Linear elasticity: a constant dP/dF, block diagonal in the basis at U = V = I.
    const Mat4 C = M::stress_derivative(Mat2::Identity(), l, false);
    const Vec4 d1(1, 0, 0, 0), d2(0, 0, 0, 1);
    const Vec4 flip = Vec4(0, 1, 1, 0) / std::sqrt(2.0);
    const Vec4 twist = Vec4(0, 1, -1, 0) / std::sqrt(2.0);
    Mat2 A;
    A << d1.dot(C * d1), d1.dot(C * d2), d2.dot(C * d1), d2.dot(C * d2);
    Vec2 a;
    symmetric_eigen(A, &a, nullptr);
    return Vec4(a(0), a(1), flip.dot(C * flip), twist.dot(C * twist));
  }
}

bool energy_is_finite(Model m, const Mat2& F) {
  return model_allows_inversion(m) || determinant(F) > 0.0;
}

// P F^T / J. For the rotation-invariant models the skew part is rounding only and is
// removed; linear elasticity's is real (the model is not rotation invariant) and kept.
Mat2 cauchy_of(Model model, const Mat2& P, const Mat2& F, double J) {
  if (J == 0.0) return Mat2::Zero();
  const Mat2 c = P * F.transpose() / J;
  if (model == Model::Linear) return c;
  return 0.5 * (c + c.transpose());
}

}  // namespace

StressAnalysis analyze_stress(Model model, const Mat2& F, const Lame& lame) {
  StressAnalysis r;
  r.model = model;
  r.lame = lame;
  r.F = F;
  r.svd = polar_svd(F);
  r.J = determinant(F);
  r.finite = energy_is_finite(model, F);
  if (!r.finite) {
    r.psi = std::numeric_limits<double>::infinity();
    return r;
  }
  visit_model(model, [&](auto m) {
    using M = decltype(m);
    r.psi = M::energy_density(F, lame);
    r.P = M::first_piola(F, lame);
    r.eigenvalues = stress_derivative_eigenvalues<M>(r.svd.sigma, lame);
  });
  r.cauchy = cauchy_of(model, r.P, F, r.J);
  symmetric_eigen(r.cauchy, &r.principal_stress, &r.principal_directions);
  r.projected_eigenvalues = r.eigenvalues.cwiseMax(0.0);
  r.clamped = static_cast<int>((r.eigenvalues.array() < 0.0).count());
  return r;
}

double energy_density_of(Model model, const Mat2& F, const Lame& lame) {
  return energy_density(model, F, lame);
}

PrincipalStress principal_stress_of(Model model, const Mat2& F, const Lame& lame) {
  PrincipalStress r;
  if (!energy_is_finite(model, F)) return r;
  const double J = determinant(F);
  const Mat2 c = cauchy_of(model, first_piola(model, F, lame), F, J);
  const double mean = 0.5 * (c(0, 0) + c(1, 1)), half_diff = 0.5 * (c(0, 0) - c(1, 1));
  const double off = 0.5 * (c(0, 1) + c(1, 0)), radius = std::hypot(half_diff, off);
  r.values = Vec2(mean + radius, mean - radius);
  // The larger eigenvalue's vector from whichever row of (c - (mean + radius) I) is the
  // longer, (radius + |half_diff|, +-off); its squared length is 2 radius (radius + |half_diff|).
  const double len2 = 2.0 * radius * (radius + std::abs(half_diff));
  if (!(len2 > 0.0)) return r;  // isotropic stress: every direction is principal
  const double inv = 1.0 / std::sqrt(len2);
  r.direction = half_diff >= 0.0 ? Vec2((radius + half_diff) * inv, off * inv)
                                 : Vec2(off * inv, (radius - half_diff) * inv);
  return r;
}

double signed_max_principal_stress(Model model, const Mat2& F, const Lame& lame) {
  const Vec2 v = principal_stress_of(model, F, lame).values;
  return std::abs(v(0)) >= std::abs(v(1)) ? v(0) : v(1);
}

int clamped_eigenvalue_count(Model model, const Mat2& F, const Lame& lame) {
  if (!energy_is_finite(model, F)) return 0;
  return visit_model(model, [&](auto m) {
    using M = decltype(m);
    Vec2 sigma(1.0, 1.0);
    if constexpr (kHasDiagonalSpace<M>) sigma = polar_svd(F).sigma;
    return static_cast<int>((stress_derivative_eigenvalues<M>(sigma, lame).array() < 0.0).count());
  });
}

Mat4 exact_stress_derivative(Model model, const Mat2& F, const Lame& lame) {
  return stress_derivative(model, F, lame, false);
}

FiniteDifferenceErrors finite_difference_errors(Model model, const Mat2& F, const Lame& lame) {
  if (!energy_is_finite(model, F)) return {};
  return finite_difference_errors(
      [&](const Mat2& G) { return energy_density(model, G, lame); }, first_piola(model, F, lame),
      exact_stress_derivative(model, F, lame), F, !model_allows_inversion(model),
      1e-4 * (lame.mu + std::abs(lame.lambda)));
}

FiniteDifferenceErrors finite_difference_errors(const std::function<double(const Mat2&)>& psi_of,
                                                const Mat2& P, const Mat4& dPdF, const Mat2& F,
                                                bool barrier, double floor) {
  FiniteDifferenceErrors e;
  const Vec2 sigma = polar_svd(F).sigma;
  if (barrier && !(sigma(1) > 0.0)) return e;  // psi is +inf at F: nothing to difference
  const double big = std::max(std::abs(sigma(0)), 1e-8);
  // A barrier model must not be stepped across J = 0: steps well inside its smallest
  // singular value.
  const double barrier_cap = barrier ? 1e-3 * sigma(1) : std::numeric_limits<double>::infinity();
  const double h1 = std::min(1e-5 * big, barrier_cap);
  const double h2 = std::min(1e-4 * big, barrier_cap);
  const Vec4 f = flatten(F);
  const auto psi = [&](const Vec4& g) { return psi_of(unflatten(g)); };
  const Mat4 I = Mat4::Identity();
  Vec4 grad;
  for (int i = 0; i < 4; ++i)
    grad(i) = (psi(f + h1 * I.col(i)) - psi(f - h1 * I.col(i))) / (2.0 * h1);
  e.P_fd = unflatten(grad);
  const double psi0 = psi(f);
  for (int i = 0; i < 4; ++i) {
    const Vec4 di = h2 * I.col(i);
    e.dPdF_fd(i, i) = (psi(f + di) - 2.0 * psi0 + psi(f - di)) / (h2 * h2);
    for (int j = i + 1; j < 4; ++j) {
      const Vec4 dj = h2 * I.col(j);
      e.dPdF_fd(i, j) = e.dPdF_fd(j, i) =
          (psi(f + di + dj) - psi(f + di - dj) - psi(f - di + dj) + psi(f - di - dj)) /
          (4.0 * h2 * h2);
    }
  }
  e.P = (P - e.P_fd).norm() / std::max(e.P_fd.norm(), floor);
  e.dPdF = (dPdF - e.dPdF_fd).norm() / std::max(e.dPdF_fd.norm(), floor);
  return e;
}

}  // namespace invfree
