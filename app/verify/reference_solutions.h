// Elasticity's exact and reference answers that `invfree verify` compares the simulator
// against: closed forms (Timoshenko-Goodier's cantilever, Kirsch's hole, homogeneous
// plane-strain tension of the lecture's neo-Hookean), engineering formulas (Timoshenko beam,
// Heywood's finite-width hole factor) and converged values for Cook's membrane. Derivations
// and citations are in docs/verification.md; this file only evaluates them.
//
// Conventions, because every formula here is plane strain per unit thickness: the 2D
// neo-Hookean with the 3D Lame constants IS the plane-strain model, so E and nu below are
// the 3D Young's modulus and Poisson ratio, and plane-stress textbook formulas are used with
// E' = E / (1 - nu^2), nu' = nu / (1 - nu). Forces are per unit thickness.
#pragma once

#include "types.h"

namespace invfree {

// ---- Plane strain -----------------------------------------------------------------------

// E' = E / (1 - nu^2): the modulus that replaces E in plane-stress formulas under plane
// strain (also the small-strain slope of uniaxial tension, see uniaxial_nominal_stress).
double plane_strain_modulus(double youngs, double poisson);
// nu' = nu / (1 - nu), the Poisson ratio that goes with E'.
double plane_strain_poisson(double poisson);

// ---- Cantilever: length L along +x from a clamp at x = 0, depth H centred on y = 0, total
// end shear P (per unit thickness) acting in -y on the end x = L ---------------------------

// Rectangle's shear coefficient: 5/6, the value whose shear energy equals that of the
// parabolic shear stress (see docs/verification.md, "Cantilever").
inline constexpr double kRectangleShearCoefficient = 5.0 / 6.0;

// Euler-Bernoulli tip deflection P L^3 / (3 E' I), I = H^3 / 12 (magnitude, along the load).
double euler_bernoulli_tip_deflection(double L, double H, double P, double E, double nu);
// Timoshenko beam: P L^3 / (3 E' I) + P L / (kappa G A), A = H, G = mu = E / (2 (1 + nu)),
// kappa = kRectangleShearCoefficient (magnitude, along the load).
double timoshenko_tip_deflection(double L, double H, double P, double E, double nu);

// Timoshenko & Goodier's exact plane solution (Theory of Elasticity, 3rd ed., section 21),
// plane strain: the end carries the parabolic shear of timoshenko_goodier_end_traction, the
// clamp holds the centroid (x = 0, y = 0) fixed with the vertical fibre there unrotated
// (du/dy = 0). Tip deflection at (L, 0): P L^3 / (3 E' I) + 3 P L / (2 G H).
double timoshenko_goodier_tip_deflection(double L, double H, double P, double E, double nu);
// The exact displacement at X = (x, y), 0 <= x <= L, |y| <= H/2. A mesh whose clamp edge is
// given these values (instead of zero) and whose end gets the parabolic traction converges
// to this field exactly, free of the clamp's Saint-Venant disturbance.
Vec2 timoshenko_goodier_displacement(const Vec2& X, double L, double H, double P, double E,
                                     double nu);
// Its stress (small strain, so Cauchy = first Piola): sigma_xx = P (L - x) y / I,
// sigma_yy = 0, sigma_xy = -(3 P / (2 H)) (1 - 4 y^2 / H^2). Independent of E and nu.
Mat2 timoshenko_goodier_stress(const Vec2& X, double L, double H, double P);
// The traction on the end x = L at height y: (0, -(3 P / (2 H)) (1 - 4 y^2 / H^2)); it
// integrates to (0, -P) with zero moment about (L, 0).
Vec2 timoshenko_goodier_end_traction(double y, double H, double P);

// ---- Plate with a circular hole (Kirsch): radius a at the origin, remote uniaxial stress
// sigma along x; theta is measured from the x axis -----------------------------------------

// The infinite plate's peak hoop stress over the remote stress: 3 (at theta = 90 degrees).
double kirsch_hoop_stress_factor_infinite();

struct PolarStress {
  double rr = 0.0;  // sigma_rr
  double tt = 0.0;  // sigma_theta_theta (hoop)
  double rt = 0.0;  // sigma_r_theta
};
// Kirsch's stress at (r, theta), r >= a. Same in plane stress and plane strain.
PolarStress kirsch_stress_polar(double r, double theta, double a, double sigma);
// The same field in Cartesian components at X (|X| >= a).
Mat2 kirsch_stress(const Vec2& X, double a, double sigma);
// Plane-strain displacement (kappa = 3 - 4 nu), zero at the hole's centre by symmetry and
// without rigid rotation: prescribing it on the outer boundary of a finite plate makes the
// finite plate's exact answer Kirsch's field.
Vec2 kirsch_displacement(const Vec2& X, double a, double sigma, double E, double nu);

// A strip of width W with a central hole of diameter d under uniaxial tension: peak stress
// over the gross-section stress (load / (W t)), Heywood's formula:
//   Kt_net = 2 + (1 - d/W)^3,  Kt_gross = Kt_net / (1 - d/W).
// Valid for 0 <= d/W < 1; within 1.6 % of Roark's fit to Howland's series solution for
// d/W <= 0.5 (docs/verification.md, "Plate with a hole").
double hole_in_strip_stress_factor(double d_over_w);
// Heywood's net-section factor (peak over load / ((W - d) t)).
double hole_in_strip_net_stress_factor(double d_over_w);
// Roark's cubic fit to Howland's solution (net section), the cross-check for Heywood:
//   Kt_net = 3 - 3.13 (d/W) + 3.66 (d/W)^2 - 1.53 (d/W)^3,  0 <= d/W <= 0.5 or so.
double hole_in_strip_net_stress_factor_roark(double d_over_w);

// ---- Cook's membrane: trapezoid (0,0), (48,44), (48,60), (0,44), left edge clamped, total
// shear F (per unit thickness) spread uniformly over the right edge, in +y ----------------

struct ElasticConstants {
  double youngs = 0.0;
  double poisson = 0.0;
};
// The plane-strain material that behaves exactly like the plane-stress material (E, nu):
// E* = E (1 + 2 nu) / (1 + nu)^2, nu* = nu / (1 + nu). Same shear modulus; its Lame lambda
// is the plane-stress 2 lambda mu / (lambda + 2 mu). Feed E*, nu* to invfree, which is plane
// strain, to pose the classic plane-stress problem.
ElasticConstants cook_membrane_plane_strain_material(double youngs_plane_stress,
                                                     double poisson_plane_stress);

// Where the vertical displacement is read. The widely quoted 23.96 is the MIDPOINT of the
// loaded edge; the top corner converges to a different number (docs/verification.md).
enum class CookPoint {
  MidEdge,  // (48, 52)
  Corner    // (48, 60)
};
Vec2 cook_membrane_point(CookPoint point);
// Vertical displacement at `point` for the classic plane-stress problem with nu = 1/3 (posed
// in invfree through cook_membrane_plane_strain_material, i.e. nu* = 1/4), scaled linearly:
// c F / E. c = 23.9677 (mid-edge; literature 23.96) or 25.189 (corner).
double cook_membrane_reference_tip_v(CookPoint point, double force, double youngs_plane_stress);
// Vertical displacement at `point` for the nearly incompressible plane-strain problem with
// nu = 0.4999 (E, nu given directly to invfree), c F / E. No citable linear-elastic value was
// found for this nu; c comes from this project's own Taylor-Hood computation (see docs).
double cook_membrane_incompressible_reference_tip_v(CookPoint point, double force, double youngs);
inline constexpr double kCookIncompressiblePoisson = 0.4999;

// ---- Large strain: plane-strain uniaxial tension of the lecture's neo-Hookean, F = diag(a, b)
// with the lateral faces traction free. Exact for any mesh (the deformation is homogeneous).

// The small-strain slope of uniaxial_nominal_stress at a = 1: 4 mu (lambda + mu) /
// (lambda + 2 mu) = E'.
double plane_strain_uniaxial_modulus(double mu, double lambda);
// The lateral stretch b > 0 with P22 = mu (b - 1/b) + lambda ln(a b) / b = 0 (unique: b P22
// increases strictly with b). a > 0.
double uniaxial_lateral_stretch(double a, double mu, double lambda);
// The nominal (first Piola) stress P11 = mu (a - 1/a) + lambda ln(a b) / a along that path.
double uniaxial_nominal_stress(double a, double mu, double lambda);
// dP11/da along the path (total derivative, the lateral stretch following).
double uniaxial_tangent_modulus(double a, double mu, double lambda);
// The stretch a with uniaxial_nominal_stress(a) = P, for loading by force: for lambda >= 0,
// P11 increases strictly with a on the path from -infinity (a -> 0) to +infinity, so a exists
// and is unique for any finite P.
double uniaxial_stretch_for_stress(double P, double mu, double lambda);

}  // namespace invfree
