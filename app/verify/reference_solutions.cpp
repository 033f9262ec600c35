#include "app/verify/reference_solutions.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace invfree {

namespace {

double shear_modulus(double E, double nu) {
  return E / (2.0 * (1.0 + nu));
}

double second_moment(double H) {
  return H * H * H / 12.0;
}

}  // namespace

double plane_strain_modulus(double youngs, double poisson) {
  return youngs / (1.0 - poisson * poisson);
}

double plane_strain_poisson(double poisson) {
  return poisson / (1.0 - poisson);
}

// ---- Cantilever ---------------------------------------------------------------------------

double euler_bernoulli_tip_deflection(double L, double H, double P, double E, double nu) {
  return P * L * L * L / (3.0 * plane_strain_modulus(E, nu) * second_moment(H));
}

double timoshenko_tip_deflection(double L, double H, double P, double E, double nu) {
  return euler_bernoulli_tip_deflection(L, H, P, E, nu) +
         P * L / (kRectangleShearCoefficient * shear_modulus(E, nu) * H);
}

double timoshenko_goodier_tip_deflection(double L, double H, double P, double E, double nu) {
  return -timoshenko_goodier_displacement(Vec2(L, 0.0), L, H, P, E, nu).y();
}

// Integrating the strains of timoshenko_goodier_stress (plane strain: E', nu'; the shear
// strain uses G, which plane strain leaves alone) and fixing the rigid motion by
// u(0,0) = v(0,0) = 0 and du/dy(0,0) = 0 gives, with c = H/2,
//   u = P (L x - x^2/2) y / (E' I) - nu' P y^3 / (6 E' I) + P y^3 / (6 I G)
//   v = -nu' P (L - x) y^2 / (2 E' I) - P (L x^2/2 - x^3/6) / (E' I) - P c^2 x / (2 I G).
Vec2 timoshenko_goodier_displacement(const Vec2& X, double L, double H, double P, double E,
                                     double nu) {
  const double Ep = plane_strain_modulus(E, nu), nup = plane_strain_poisson(nu);
  const double G = shear_modulus(E, nu), I = second_moment(H), c = 0.5 * H;
  const double x = X.x(), y = X.y();
  const double u = P * (L * x - 0.5 * x * x) * y / (Ep * I) - nup * P * y * y * y / (6.0 * Ep * I) +
                   P * y * y * y / (6.0 * I * G);
  const double v = -nup * P * (L - x) * y * y / (2.0 * Ep * I) -
                   P * (0.5 * L * x * x - x * x * x / 6.0) / (Ep * I) -
                   P * c * c * x / (2.0 * I * G);
  return {u, v};
}

Mat2 timoshenko_goodier_stress(const Vec2& X, double L, double H, double P) {
  const double x = X.x(), y = X.y();
  const double sxx = P * (L - x) * y / second_moment(H);
  const double sxy = -1.5 * P / H * (1.0 - 4.0 * y * y / (H * H));
  Mat2 s;
  s << sxx, sxy, sxy, 0.0;
  return s;
}

Vec2 timoshenko_goodier_end_traction(double y, double H, double P) {
  return {0.0, -1.5 * P / H * (1.0 - 4.0 * y * y / (H * H))};
}

// ---- Plate with a hole --------------------------------------------------------------------

double kirsch_hoop_stress_factor_infinite() {
  return 3.0;
}

PolarStress kirsch_stress_polar(double r, double theta, double a, double sigma) {
  const double q2 = a * a / (r * r), q4 = q2 * q2;
  const double c2 = std::cos(2.0 * theta), s2 = std::sin(2.0 * theta);
  PolarStress s;
  s.rr = 0.5 * sigma * (1.0 - q2) + 0.5 * sigma * (1.0 - 4.0 * q2 + 3.0 * q4) * c2;
  s.tt = 0.5 * sigma * (1.0 + q2) - 0.5 * sigma * (1.0 + 3.0 * q4) * c2;
  s.rt = -0.5 * sigma * (1.0 + 2.0 * q2 - 3.0 * q4) * s2;
  return s;
}

Mat2 kirsch_stress(const Vec2& X, double a, double sigma) {
  const double r = X.norm(), theta = std::atan2(X.y(), X.x());
  const PolarStress p = kirsch_stress_polar(r, theta, a, sigma);
  const double c = std::cos(theta), s = std::sin(theta);
  // sigma = Q diag-block Q^T with Q = [e_r e_theta].
  Mat2 Q, polar;
  Q << c, -s, s, c;
  polar << p.rr, p.rt, p.rt, p.tt;
  return Q * polar * Q.transpose();
}

Vec2 kirsch_displacement(const Vec2& X, double a, double sigma, double E, double nu) {
  const double mu = shear_modulus(E, nu), kappa = 3.0 - 4.0 * nu;
  const double r = X.norm(), theta = std::atan2(X.y(), X.x());
  const double ra = r / a, ar = a / r, ar3 = ar * ar * ar;
  const double c1 = std::cos(theta), s1 = std::sin(theta);
  const double c3 = std::cos(3.0 * theta), s3 = std::sin(3.0 * theta);
  const double k = sigma * a / (8.0 * mu);
  const double ux =
      k * (ra * (kappa + 1.0) * c1 + 2.0 * ar * ((1.0 + kappa) * c1 + c3) - 2.0 * ar3 * c3);
  const double uy =
      k * (ra * (kappa - 3.0) * s1 + 2.0 * ar * ((1.0 - kappa) * s1 + s3) - 2.0 * ar3 * s3);
  return {ux, uy};
}

double hole_in_strip_net_stress_factor(double d_over_w) {
  const double m = 1.0 - d_over_w;
  return 2.0 + m * m * m;
}

double hole_in_strip_stress_factor(double d_over_w) {
  return hole_in_strip_net_stress_factor(d_over_w) / (1.0 - d_over_w);
}

double hole_in_strip_net_stress_factor_roark(double d_over_w) {
  const double x = d_over_w;
  return 3.0 - 3.13 * x + 3.66 * x * x - 1.53 * x * x * x;
}

// ---- Cook's membrane ----------------------------------------------------------------------

ElasticConstants cook_membrane_plane_strain_material(double youngs_plane_stress,
                                                     double poisson_plane_stress) {
  const double nu = poisson_plane_stress;
  return {youngs_plane_stress * (1.0 + 2.0 * nu) / ((1.0 + nu) * (1.0 + nu)), nu / (1.0 + nu)};
}

Vec2 cook_membrane_point(CookPoint point) {
  return point == CookPoint::Corner ? Vec2(48.0, 60.0) : Vec2(48.0, 52.0);
}

// Each constant is v E / F at unit thickness, from this project's Taylor-Hood (P2
// displacement, P1 pressure, p = lambda div u) solves on 4..256 cells per side, Richardson
// extrapolated from the last three (docs/verification.md, "Cook's membrane"). The corner
// converges slower (rate ~1 in h) because the traction jumps there.
namespace {
constexpr double kCookMid = 23.9677;                  // plane stress nu = 1/3 (literature 23.96)
constexpr double kCookCorner = 25.189;                // the same problem at (48, 60)
constexpr double kCookIncompressibleMid = 18.512;     // plane strain nu = 0.4999, (48, 52)
constexpr double kCookIncompressibleCorner = 19.428;  // the same at (48, 60)
}  // namespace

double cook_membrane_reference_tip_v(CookPoint point, double force, double youngs_plane_stress) {
  return (point == CookPoint::Corner ? kCookCorner : kCookMid) * force / youngs_plane_stress;
}

double cook_membrane_incompressible_reference_tip_v(CookPoint point, double force, double youngs) {
  const double c = point == CookPoint::Corner ? kCookIncompressibleCorner : kCookIncompressibleMid;
  return c * force / youngs;
}

// ---- Large strain -------------------------------------------------------------------------

double plane_strain_uniaxial_modulus(double mu, double lambda) {
  return 4.0 * mu * (lambda + mu) / (lambda + 2.0 * mu);
}

// b P22 = mu (b^2 - 1) + lambda (ln a + s), s = ln b, is increasing and convex in s. Newton
// started where it is >= 0 (s = max(0, -ln a): there it equals lambda ln a for a >= 1 and
// mu (1/a^2 - 1) for a < 1) walks down to the root monotonically and never overshoots, so it
// needs no bracket; it stops when rounding makes the residual non-positive or the step stops
// moving s (quadratic convergence: a handful of iterations).
double uniaxial_lateral_stretch(double a, double mu, double lambda) {
  const double ln_a = std::log(a);
  double s = std::max(0.0, -ln_a);
  for (int it = 0; it < 200; ++it) {
    const double e2s = std::exp(2.0 * s);
    const double g = mu * (e2s - 1.0) + lambda * (ln_a + s);
    const double dg = 2.0 * mu * e2s + lambda;
    const double step = g / dg;
    if (!(step > 0.0)) break;  // at the root (g <= 0 only through rounding)
    const double next = s - step;
    if (next == s) break;
    s = next;
  }
  return std::exp(s);
}

double uniaxial_nominal_stress(double a, double mu, double lambda) {
  const double b = uniaxial_lateral_stretch(a, mu, lambda);
  return mu * (a - 1.0 / a) + lambda * std::log(a * b) / a;
}

// With Psi(a, b) the diagonal energy, P11 = Psi_a and P22 = Psi_b = 0 on the path, so
// dP11/da = Psi_aa - Psi_ab^2 / Psi_bb (the lateral stretch adjusts to keep P22 = 0).
double uniaxial_tangent_modulus(double a, double mu, double lambda) {
  const double b = uniaxial_lateral_stretch(a, mu, lambda);
  const double ln_j = std::log(a * b);
  const double paa = mu * (1.0 + 1.0 / (a * a)) + lambda * (1.0 - ln_j) / (a * a);
  const double pbb = mu * (1.0 + 1.0 / (b * b)) + lambda * (1.0 - ln_j) / (b * b);
  const double pab = lambda / (a * b);
  return paa - pab * pab / pbb;
}

// Safeguarded Newton in t = ln a: P11 is strictly increasing in t, so a bracket [lo, hi]
// found by doubling outwards from t = 0 always holds the root; a Newton step that leaves the
// bracket is replaced by bisection.
double uniaxial_stretch_for_stress(double P, double mu, double lambda) {
  auto residual = [&](double t) { return uniaxial_nominal_stress(std::exp(t), mu, lambda) - P; };
  if (P == 0.0) return 1.0;
  double lo = 0.0, hi = 0.0;
  if (P > 0.0) {
    hi = 1.0;
    while (residual(hi) < 0.0) lo = hi, hi *= 2.0;
  } else {
    lo = -1.0;
    while (residual(lo) > 0.0) hi = lo, lo *= 2.0;
  }
  double t = 0.5 * (lo + hi);
  for (int it = 0; it < 200; ++it) {
    const double r = residual(t);
    if (r == 0.0) return std::exp(t);
    (r < 0.0 ? lo : hi) = t;
    const double a = std::exp(t);
    double next = t - r / (uniaxial_tangent_modulus(a, mu, lambda) * a);  // dP/dt = a dP/da
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == t || hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(t))
      return std::exp(next);
    t = next;
  }
  return std::exp(t);
}

}  // namespace invfree
