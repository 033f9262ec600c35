// app/verify/reference_solutions.*: the closed forms checked against what defines them, not
// against copies of themselves. Displacement fields are differentiated numerically and put
// through plane-strain Hooke's law to meet the stress formulas; stresses are checked for
// equilibrium and their boundary conditions; the beam formulas against their limits; the
// uniaxial neo-Hookean path against the simulator's own NeoHookean::first_piola. Each
// tolerance says where it comes from.
#include "app/verify/reference_solutions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "material/material.h"
#include "material/neo_hookean.h"

namespace invfree {
namespace {

constexpr double kPi = std::numbers::pi;

// Plane-strain Hooke's law: sigma = lambda tr(eps) I + 2 mu eps.
Mat2 hooke(const Mat2& eps, const Lame& m) {
  return m.lambda * eps.trace() * Mat2::Identity() + 2.0 * m.mu * eps;
}

// Symmetric gradient of a displacement field by central differences with step h. For the
// cubic Timoshenko-Goodier field the truncation error is h^2/6 |u'''|; for Kirsch's field
// it is of the same order relative to |u| / a^3.
template <class Field>
Mat2 strain_by_differences(const Field& u, const Vec2& X, double h) {
  Mat2 grad;
  for (int j = 0; j < 2; ++j) {
    Vec2 e = Vec2::Zero();
    e(j) = h;
    grad.col(j) = (u(X + e) - u(X - e)) / (2.0 * h);
  }
  return 0.5 * (grad + grad.transpose());
}

// Divergence of a stress field by central differences.
template <class Stress>
Vec2 divergence_by_differences(const Stress& s, const Vec2& X, double h) {
  const Vec2 ex(h, 0.0), ey(0.0, h);
  const Mat2 dx = (s(X + ex) - s(X - ex)) / (2.0 * h), dy = (s(X + ey) - s(X - ey)) / (2.0 * h);
  return {dx(0, 0) + dy(0, 1), dx(1, 0) + dy(1, 1)};
}

double max_abs(const Mat2& m) {
  return m.cwiseAbs().maxCoeff();
}

// ---- Plane strain ------------------------------------------------------------------------

TEST(PlaneStrain, ModulusIsTheUniaxialPlaneStrainModulusOfTheLameConstants) {
  for (double nu : {0.0, 0.25, 1.0 / 3.0, 0.45, 0.499}) {
    const Lame m = lame_from_young_poisson(7.0, nu);
    // Two spellings of one number: only rounding (a few ulps) separates them.
    EXPECT_NEAR(plane_strain_modulus(7.0, nu), plane_strain_uniaxial_modulus(m.mu, m.lambda),
                1e-13 * plane_strain_modulus(7.0, nu))
        << "nu " << nu;
    // nu' = lambda / (lambda + 2 mu): the plane-strain lateral contraction.
    EXPECT_NEAR(plane_strain_poisson(nu), m.lambda / (m.lambda + 2.0 * m.mu), 1e-13) << nu;
  }
}

// ---- Cantilever -------------------------------------------------------------------------

constexpr double kE = 1000.0, kNu = 0.3, kP = 2.0;

TEST(Cantilever, TimoshenkoTendsToEulerBernoulliWithTheDerivedShearRatio) {
  const double L = 10.0;
  const double Ep = kE / (1.0 - kNu * kNu), G = kE / (2.0 * (1.0 + kNu));
  for (double H : {2.0, 1.0, 0.1, 0.01}) {
    const double eb = euler_bernoulli_tip_deflection(L, H, kP, kE, kNu);
    EXPECT_NEAR(eb, kP * L * L * L / (3.0 * Ep * H * H * H / 12.0), 1e-12 * eb);
    // (P L / (kappa G H)) / (P L^3 / (3 E' H^3 / 12)) = E' H^2 / (4 kappa G L^2): the shear
    // part's share falls as (H/L)^2. Both sides are a handful of flops (1e-12 relative), but
    // the difference of two deflections loses up to 2 eps of the whole in absolute terms.
    const double ratio = (timoshenko_tip_deflection(L, H, kP, kE, kNu) - eb) / eb;
    EXPECT_NEAR(ratio, Ep * H * H / (4.0 * kRectangleShearCoefficient * G * L * L),
                1e-12 * ratio + 4.0 * std::numeric_limits<double>::epsilon())
        << "H " << H;
  }
  // A slender beam: the shear share is 0.3 E'/G (H/L)^2 = 7.4e-6 at H/L = 1e-3.
  const double eb = euler_bernoulli_tip_deflection(L, 0.01, kP, kE, kNu);
  EXPECT_LT(timoshenko_tip_deflection(L, 0.01, kP, kE, kNu) / eb - 1.0, 1e-5);
}

TEST(Cantilever, ShearCoefficientFiveSixthsEqualsTheParabolicShearEnergy) {
  // Shear energy per length of tau = (3V/2H)(1 - 4y^2/H^2) over [-H/2, H/2] against that of
  // a uniform tau = V/H: their ratio is 1/kappa. Simpson's rule integrates the quartic
  // integrand with error ~ (step)^4: 2000 intervals put it below 1e-12.
  const double H = 1.0, V = 1.0;
  const int n = 2000;
  double integral = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double y = -0.5 * H + H * i / n;
    const double tau = 1.5 * V / H * (1.0 - 4.0 * y * y / (H * H));
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    integral += w * tau * tau;
  }
  integral *= H / n / 3.0;
  EXPECT_NEAR(integral / (V * V / H), 1.0 / kRectangleShearCoefficient, 1e-12);
}

TEST(Cantilever, TimoshenkoGoodierDisplacementGivesItsStressThroughPlaneStrainHooke) {
  const double L = 8.0, H = 1.0;
  const Lame m = lame_from_young_poisson(kE, kNu);
  auto u = [&](const Vec2& X) { return timoshenko_goodier_displacement(X, L, H, kP, kE, kNu); };
  const Mat2 scale = timoshenko_goodier_stress(Vec2(0.0, 0.5 * H), L, H, kP);  // the largest
  for (const Vec2& X : {Vec2(0.0, 0.5), Vec2(0.0, -0.3), Vec2(2.0, 0.1), Vec2(5.5, -0.45),
                        Vec2(8.0, 0.0), Vec2(8.0, 0.4), Vec2(3.3, 0.25)}) {
    // h = 1e-4 L: truncation h^2/6 |u'''| ~ 1e-9 of the stress, rounding eps |u| / h ~ 1e-11.
    const Mat2 sigma = hooke(strain_by_differences(u, X, 1e-4 * L), m);
    EXPECT_LT(max_abs(sigma - timoshenko_goodier_stress(X, L, H, kP)), 1e-7 * max_abs(scale))
        << "at " << X.transpose() << "\n"
        << sigma << "\nvs\n"
        << timoshenko_goodier_stress(X, L, H, kP);
  }
}

TEST(Cantilever, TimoshenkoGoodierStressIsInEquilibriumWithItsLoads) {
  const double L = 8.0, H = 1.0;
  auto s = [&](const Vec2& X) { return timoshenko_goodier_stress(X, L, H, kP); };
  const double scale = kP * L * 0.5 * H / (H * H * H / 12.0);
  for (const Vec2& X : {Vec2(1.0, 0.2), Vec2(4.0, -0.4), Vec2(7.9, 0.0)})
    // The stress is at most quadratic: central differences are exact up to rounding.
    EXPECT_LT(divergence_by_differences(s, X, 1e-3).norm(), 1e-9 * scale) << X.transpose();
  // Top and bottom faces are traction free: sigma n = 0 with n = (0, +-1), exactly.
  for (double x : {0.0, 2.5, 8.0}) {
    EXPECT_EQ((s(Vec2(x, 0.5 * H)) * Vec2(0.0, 1.0)).norm(), 0.0);
    EXPECT_EQ((s(Vec2(x, -0.5 * H)) * Vec2(0.0, -1.0)).norm(), 0.0);
  }
  // The end x = L: sigma e_x is the parabolic traction; three-point Gauss integrates its
  // quadratic exactly, so the resultant is (0, -P) and the moment zero up to rounding.
  Vec2 force = Vec2::Zero();
  double moment = 0.0;
  const double gx[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  for (int q = 0; q < 3; ++q) {
    const double y = 0.5 * H * gx[q];
    const Vec2 t = timoshenko_goodier_end_traction(y, H, kP);
    EXPECT_LT((s(Vec2(L, y)) * Vec2(1.0, 0.0) - t).norm(), 1e-15 * kP / H);
    force += 0.5 * H * gw[q] * t;
    moment += 0.5 * H * gw[q] * (-y * t.x());
  }
  EXPECT_NEAR(force.x(), 0.0, 1e-15 * kP);
  EXPECT_NEAR(force.y(), -kP, 1e-14 * kP);
  EXPECT_NEAR(moment, 0.0, 1e-15 * kP * H);
}

TEST(Cantilever, TimoshenkoGoodierClampAndTipDeflection) {
  const double L = 8.0, H = 1.0;
  auto u = [&](const Vec2& X) { return timoshenko_goodier_displacement(X, L, H, kP, kE, kNu); };
  // The clamp condition: centroid fixed, vertical fibre there unrotated (du/dy = 0).
  EXPECT_EQ(u(Vec2(0.0, 0.0)).norm(), 0.0);
  // u is cubic in y on the clamp: the central difference is the exact du/dy(0,0) plus
  // h^2 times the y^3 coefficient (~1e-2 here), so h = 1e-6 leaves ~1e-14.
  const double h = 1e-6;
  EXPECT_NEAR((u(Vec2(0.0, h)).x() - u(Vec2(0.0, -h)).x()) / (2.0 * h), 0.0, 1e-12);
  // The tip moves along the load, by the function of the same name.
  const double tip = timoshenko_goodier_tip_deflection(L, H, kP, kE, kNu);
  EXPECT_DOUBLE_EQ(-u(Vec2(L, 0.0)).y(), tip);
  // Against the beam formulas: T&G = EB + 3 P L / (2 G H), i.e. Timoshenko's shear term with
  // kappa = 2/3 instead of 5/6, the difference 0.3 P L / (G H) (clamp condition, not energy).
  const double G = kE / (2.0 * (1.0 + kNu));
  EXPECT_NEAR(tip - euler_bernoulli_tip_deflection(L, H, kP, kE, kNu), 1.5 * kP * L / (G * H),
              1e-12 * tip);
  EXPECT_NEAR(tip - timoshenko_tip_deflection(L, H, kP, kE, kNu), 0.3 * kP * L / (G * H),
              1e-12 * tip);
  // Linear in P.
  EXPECT_NEAR(timoshenko_goodier_tip_deflection(L, H, 3.0 * kP, kE, kNu), 3.0 * tip, 1e-12 * tip);
}

// ---- Plate with a hole -------------------------------------------------------------------

TEST(Kirsch, HoleEdgeIsTractionFreeWithHoopStressThreeSigmaAcrossTheLoad) {
  const double a = 0.7, sigma = 5.0;
  EXPECT_EQ(kirsch_hoop_stress_factor_infinite(), 3.0);
  for (int k = 0; k <= 24; ++k) {
    const double theta = 2.0 * kPi * k / 24;
    const PolarStress s = kirsch_stress_polar(a, theta, a, sigma);
    // At r = a the bracketed factors vanish identically; only rounding of cos/sin remains.
    EXPECT_NEAR(s.rr, 0.0, 1e-14 * sigma) << theta;
    EXPECT_NEAR(s.rt, 0.0, 1e-14 * sigma) << theta;
    EXPECT_NEAR(s.tt, sigma * (1.0 - 2.0 * std::cos(2.0 * theta)), 1e-14 * sigma) << theta;
  }
  EXPECT_NEAR(kirsch_stress_polar(a, 0.5 * kPi, a, sigma).tt, 3.0 * sigma, 1e-14 * sigma);
  EXPECT_NEAR(kirsch_stress_polar(a, 0.0, a, sigma).tt, -sigma, 1e-14 * sigma);
  // Cartesian at the top of the hole (theta = 90 degrees): hoop = sigma_xx there.
  const Mat2 top = kirsch_stress(Vec2(0.0, a), a, sigma);
  EXPECT_NEAR(top(0, 0), 3.0 * sigma, 1e-13 * sigma);
  EXPECT_NEAR(top(1, 1), 0.0, 1e-13 * sigma);
  EXPECT_NEAR(top(0, 1), 0.0, 1e-13 * sigma);
  // Far away the plate sees only the remote stress: the disturbance decays as (a/r)^2.
  const Mat2 far = kirsch_stress(Vec2(3e3 * a, 4e3 * a), a, sigma);
  EXPECT_LT(max_abs(far - Mat2{{sigma, 0.0}, {0.0, 0.0}}), 1e-6 * sigma);
}

TEST(Kirsch, StressIsInEquilibrium) {
  const double a = 1.0, sigma = 2.0;
  auto s = [&](const Vec2& X) { return kirsch_stress(X, a, sigma); };
  for (const Vec2& X : {Vec2(1.2, 0.3), Vec2(-0.4, 1.5), Vec2(2.0, -2.0), Vec2(0.0, -1.1)})
    // h = 1e-4: truncation h^2 |s'''| ~ 1e-8 sigma near the hole.
    EXPECT_LT(divergence_by_differences(s, X, 1e-4).norm(), 1e-6 * sigma) << X.transpose();
}

TEST(Kirsch, PlaneStrainDisplacementGivesTheStressThroughHooke) {
  const double a = 1.0, sigma = 3.0;
  for (double nu : {0.0, 0.3, 0.49}) {
    const double E = 200.0;
    const Lame m = lame_from_young_poisson(E, nu);
    auto u = [&](const Vec2& X) { return kirsch_displacement(X, a, sigma, E, nu); };
    for (const Vec2& X : {Vec2(1.0, 0.0), Vec2(0.0, 1.0), Vec2(0.8, 0.8), Vec2(-1.7, 0.4),
                          Vec2(3.0, -5.0), Vec2(-0.3, -1.2)}) {
      if (X.norm() < a) continue;
      // h = 1e-5 a: truncation ~1e-10 sigma, rounding eps |u| / h ~ 1e-10 sigma.
      const Mat2 s = hooke(strain_by_differences(u, X, 1e-5 * a), m);
      EXPECT_LT(max_abs(s - kirsch_stress(X, a, sigma)), 1e-7 * sigma)
          << "nu " << nu << " at " << X.transpose() << "\n"
          << s << "\nvs\n"
          << kirsch_stress(X, a, sigma);
    }
    // Symmetric about both axes: u_y = 0 on y = 0, u_x = 0 on x = 0.
    EXPECT_NEAR(u(Vec2(2.0, 0.0)).y(), 0.0, 1e-15);
    EXPECT_NEAR(u(Vec2(0.0, 2.0)).x(), 0.0, 1e-15);
  }
}

TEST(HoleInStrip, HeywoodStartsAtKirschAndStaysWithinHowlandsFit) {
  EXPECT_EQ(hole_in_strip_net_stress_factor(0.0), 3.0);
  EXPECT_EQ(hole_in_strip_stress_factor(0.0), 3.0);
  EXPECT_EQ(hole_in_strip_net_stress_factor_roark(0.0), 3.0);
  double last_net = 3.0, last_gross = 3.0, worst = 0.0;
  for (int k = 1; k <= 50; ++k) {
    const double r = 0.01 * k;
    const double net = hole_in_strip_net_stress_factor(r), gross = hole_in_strip_stress_factor(r);
    EXPECT_NEAR(gross, net / (1.0 - r), 1e-14 * gross);
    // The net-section factor falls from 3 towards 2 (a narrow ligament is nearly uniformly
    // stressed); the gross factor rises (the ligament shrinks faster).
    EXPECT_LT(net, last_net);
    EXPECT_GT(gross, last_gross);
    last_net = net;
    last_gross = gross;
    const double howland = hole_in_strip_net_stress_factor_roark(r);
    worst = std::max(worst, std::abs(net - howland) / howland);
  }
  // The documented accuracy (docs/verification.md): 1.6 % up to d/W = 0.5, worst at 0.5.
  EXPECT_LT(worst, 0.016);
  EXPECT_GT(worst, 0.01);  // and not trivially: the two formulas are different
}

// ---- Cook's membrane ---------------------------------------------------------------------

TEST(CookMembrane, PlaneStrainMaterialHasThePlaneStressCompliance) {
  for (double nu : {0.0, 0.2, 1.0 / 3.0, 0.45}) {
    const double E = 3.5;
    const ElasticConstants s = cook_membrane_plane_strain_material(E, nu);
    // In-plane compliance of plane strain (E*, nu*): eps11 = ((1 - nu*^2) s11 - nu* (1 + nu*)
    // s22) / E*; of plane stress (E, nu): (s11 - nu s22) / E. Equal coefficients:
    EXPECT_NEAR((1.0 - s.poisson * s.poisson) / s.youngs, 1.0 / E, 1e-14 / E) << nu;
    EXPECT_NEAR(s.poisson * (1.0 + s.poisson) / s.youngs, nu / E, 1e-14 / E) << nu;
    // Same shear modulus, and the plane-strain lambda is the plane-stress 2 lambda mu /
    // (lambda + 2 mu) of the original material.
    const Lame orig = lame_from_young_poisson(E, nu),
               mapped = lame_from_young_poisson(s.youngs, s.poisson);
    EXPECT_NEAR(mapped.mu, orig.mu, 1e-14 * orig.mu) << nu;
    EXPECT_NEAR(mapped.lambda, 2.0 * orig.lambda * orig.mu / (orig.lambda + 2.0 * orig.mu),
                1e-14 * orig.mu)
        << nu;
  }
  // The classic nu = 1/3: E* = 15/16 E, nu* = 1/4.
  const ElasticConstants c = cook_membrane_plane_strain_material(1.0, 1.0 / 3.0);
  EXPECT_NEAR(c.youngs, 15.0 / 16.0, 1e-15);
  EXPECT_NEAR(c.poisson, 0.25, 1e-15);
}

TEST(CookMembrane, ReferenceValuesScaleWithForceOverModulus) {
  EXPECT_EQ(cook_membrane_point(CookPoint::MidEdge), Vec2(48.0, 52.0));
  EXPECT_EQ(cook_membrane_point(CookPoint::Corner), Vec2(48.0, 60.0));
  // The literature's 23.96 (mid-edge, E = 1, F = 1) to the digits quoted.
  EXPECT_NEAR(cook_membrane_reference_tip_v(CookPoint::MidEdge, 1.0, 1.0), 23.96, 0.01);
  for (CookPoint p : {CookPoint::MidEdge, CookPoint::Corner}) {
    const double v = cook_membrane_reference_tip_v(p, 1.0, 1.0);
    EXPECT_NEAR(cook_membrane_reference_tip_v(p, 100.0, 70.0), v * 100.0 / 70.0, 1e-13 * v);
    const double w = cook_membrane_incompressible_reference_tip_v(p, 1.0, 1.0);
    EXPECT_NEAR(cook_membrane_incompressible_reference_tip_v(p, 100.0, 250.0), w * 0.4, 1e-13 * w);
    // Incompressibility stiffens the membrane.
    EXPECT_LT(w, v);
  }
  // The corner rises above the mid-edge point (the end face stretches vertically).
  EXPECT_GT(cook_membrane_reference_tip_v(CookPoint::Corner, 1.0, 1.0),
            cook_membrane_reference_tip_v(CookPoint::MidEdge, 1.0, 1.0));
}

// ---- Large strain: plane-strain uniaxial tension ------------------------------------------

struct Material {
  double nu;
  Lame lame;
};
std::vector<Material> materials() {
  std::vector<Material> out;
  for (double nu : {0.0, 0.2, 0.3, 0.45, 0.49, 0.4999})
    out.push_back({nu, lame_from_young_poisson(1.0, nu)});
  return out;
}
std::vector<double> stretches() {
  std::vector<double> out;
  for (double a = 0.2; a <= 5.0 + 1e-12; a += 0.05) out.push_back(a);
  return out;
}

TEST(UniaxialNeoHookean, LateralFacesAreTractionFree) {
  for (const Material& mat : materials())
    for (double a : stretches()) {
      const double b = uniaxial_lateral_stretch(a, mat.lame.mu, mat.lame.lambda);
      ASSERT_GT(b, 0.0);
      const double p22 = mat.lame.mu * (b - 1.0 / b) + mat.lame.lambda * std::log(a * b) / b;
      // The terms are of size (mu + lambda) / b; Newton stops at rounding (a few eps of them).
      EXPECT_LT(std::abs(p22), 1e-12 * (mat.lame.mu + mat.lame.lambda) / std::min(b, 1.0))
          << "nu " << mat.nu << " a " << a << " b " << b;
    }
}

TEST(UniaxialNeoHookean, AgreesWithTheSimulatorsNeoHookean) {
  for (const Material& mat : materials())
    for (double a : {0.3, 0.8, 1.0, 1.7, 3.0}) {
      const double b = uniaxial_lateral_stretch(a, mat.lame.mu, mat.lame.lambda);
      Mat2 F = Mat2::Zero();
      F(0, 0) = a;
      F(1, 1) = b;
      const Mat2 P = NeoHookean::first_piola(F, mat.lame);
      const double scale = mat.lame.mu + mat.lame.lambda;
      EXPECT_NEAR(P(0, 0), uniaxial_nominal_stress(a, mat.lame.mu, mat.lame.lambda), 1e-12 * scale)
          << "nu " << mat.nu << " a " << a;
      EXPECT_NEAR(P(1, 1), 0.0, 1e-12 * scale / std::min(b, 1.0)) << "nu " << mat.nu << " a " << a;
      EXPECT_EQ(P(0, 1), 0.0);
      EXPECT_EQ(P(1, 0), 0.0);
    }
}

TEST(UniaxialNeoHookean, UnstressedAtRestWithThePlaneStrainSlope) {
  for (const Material& mat : materials()) {
    const double mu = mat.lame.mu, lambda = mat.lame.lambda;
    EXPECT_EQ(uniaxial_lateral_stretch(1.0, mu, lambda), 1.0);
    EXPECT_EQ(uniaxial_nominal_stress(1.0, mu, lambda), 0.0);
    // Linear plane strain with sigma22 = 0: eps22 = -lambda / (lambda + 2 mu) eps11, so
    // sigma11 = ((lambda + 2 mu) - lambda^2 / (lambda + 2 mu)) eps11 = 4 mu (lambda + mu) /
    // (lambda + 2 mu) eps11 = E' eps11.
    const double Ep = plane_strain_uniaxial_modulus(mu, lambda);
    EXPECT_NEAR(Ep, plane_strain_modulus(1.0, mat.nu), 1e-12 * Ep);
    EXPECT_NEAR(uniaxial_tangent_modulus(1.0, mu, lambda), Ep, 1e-12 * Ep) << mat.nu;
    // Central difference, h = 1e-4: truncation h^2/6 |P'''| ~ 1e-9 Ep; rounding
    // eps (mu + lambda) / h ~ 1e-12 (mu + lambda), and lambda / Ep ~ 1e3 at nu = 0.4999.
    const double h = 1e-4;
    const double slope = (uniaxial_nominal_stress(1.0 + h, mu, lambda) -
                          uniaxial_nominal_stress(1.0 - h, mu, lambda)) /
                         (2.0 * h);
    EXPECT_NEAR(slope, Ep, 1e-6 * Ep) << mat.nu;
  }
}

TEST(UniaxialNeoHookean, TangentIsTheDerivativeAndPositive) {
  for (const Material& mat : materials()) {
    const double mu = mat.lame.mu, lambda = mat.lame.lambda;
    double last = -std::numeric_limits<double>::infinity();
    for (double a : stretches()) {
      const double k = uniaxial_tangent_modulus(a, mu, lambda);
      EXPECT_GT(k, 0.0) << "nu " << mat.nu << " a " << a;
      const double p = uniaxial_nominal_stress(a, mu, lambda);
      EXPECT_GT(p, last) << "nu " << mat.nu << " a " << a;  // strictly increasing
      last = p;
      const double h = 1e-5 * a;
      const double fd = (uniaxial_nominal_stress(a + h, mu, lambda) -
                         uniaxial_nominal_stress(a - h, mu, lambda)) /
                        (2.0 * h);
      // Truncation (h^2) ~ 1e-10 k; rounding eps (mu + lambda) / h ~ 1e-11 (mu + lambda) / a.
      EXPECT_NEAR(fd, k, 1e-6 * k + 1e-9 * (mu + lambda)) << "nu " << mat.nu << " a " << a;
    }
  }
}

TEST(UniaxialNeoHookean, StretchForStressInvertsTheNominalStress) {
  for (const Material& mat : materials())
    for (double a : stretches()) {
      const double P = uniaxial_nominal_stress(a, mat.lame.mu, mat.lame.lambda);
      const double back = uniaxial_stretch_for_stress(P, mat.lame.mu, mat.lame.lambda);
      // P is recomputed from a to rounding, and dP/da >= mu: 1e-10 leaves room for the
      // condition number (mu + lambda) / mu ~ 2.5e3 at nu = 0.4999 times a few eps.
      EXPECT_NEAR(back, a, 1e-10 * a) << "nu " << mat.nu << " P " << P;
    }
  // Large loads in both directions still converge.
  const Lame m = lame_from_young_poisson(1.0, 0.3);
  const double big = uniaxial_stretch_for_stress(1e3, m.mu, m.lambda);
  EXPECT_NEAR(uniaxial_nominal_stress(big, m.mu, m.lambda), 1e3, 1e-10 * 1e3);
  const double small = uniaxial_stretch_for_stress(-1e3, m.mu, m.lambda);
  EXPECT_GT(small, 0.0);
  EXPECT_NEAR(uniaxial_nominal_stress(small, m.mu, m.lambda), -1e3, 1e-9 * 1e3);
}

TEST(UniaxialNeoHookean, NearlyIncompressibleLimitIsIsochoric) {
  // lambda -> infinity: b -> 1/a and P11 -> mu (a - 1/a^3) (plane-strain incompressible
  // neo-Hookean). The deviation is O(mu / lambda): 1e-5 relative at nu = 0.499995.
  const Lame m = lame_from_young_poisson(1.0, 0.499995);
  for (double a : {0.5, 1.5, 3.0}) {
    EXPECT_NEAR(uniaxial_lateral_stretch(a, m.mu, m.lambda) * a, 1.0, 1e-4) << a;
    const double limit = m.mu * (a - 1.0 / (a * a * a));
    EXPECT_NEAR(uniaxial_nominal_stress(a, m.mu, m.lambda), limit, 1e-4 * std::abs(limit)) << a;
  }
}

}  // namespace
}  // namespace invfree
