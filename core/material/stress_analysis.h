// One triangle's stress and stress derivative, the lecture's way, laid open: F, its polar
// SVD, Psi, the first Piola-Kirchhoff stress P, the Cauchy stress and its principal values,
// and the four eigenvalues of dP/dF (= d2Psi/dF2 as a 4x4) from the diagonal-space analysis
// (the 2x2 Hessian in sigma, the flip and the twist; material/diagonal_space.h) before and
// after the PSD projection that clamps the negative ones. `invfree inspect`, the live
// inspector, the triangle colourings and the landscape all read it.
//
// The eigenvalues come in the order of their eigenvectors: the two scaling modes (the A
// block's eigenvalues, larger first), the flip (u1 v2^T + u2 v1^T) and the twist
// (u2 v1^T - u1 v2^T). Linear elasticity is not isotropic in that sense but its dP/dF is a
// constant matrix that the same basis at U = V = I diagonalises (scaling 2mu + 2lambda and
// 2mu, flip 2mu, twist 0), so it is reported in that basis.
//
// finite_difference_errors checks P and dP/dF against central differences of Psi alone
// (no derivative code involved): the relative Frobenius distance of each.
//
// The Cauchy stress is P F^T / J as the lecture defines it. For the rotation-invariant
// models it is symmetric (up to rounding, which is removed); linear elasticity is not
// rotation invariant, so its P F^T / J keeps the skew part it has (zero only at
// symmetric F): that is the model's flaw, shown rather than hidden. The principal
// stresses are the eigenpairs of the symmetric part (the whole tensor but for linear).
#pragma once

#include <array>
#include <functional>

#include "material/material.h"
#include "material/polar_svd.h"
#include "types.h"

namespace invfree {

// The names of the four eigenvalues, in their order.
inline constexpr std::array<const char*, 4> kEigenvalueNames{"scale 1", "scale 2", "flip", "twist"};

struct StressAnalysis {
  Model model = Model::NeoHookean;
  Lame lame;
  Mat2 F = Mat2::Identity();
  PolarSvd svd{Mat2::Identity(), Vec2(1.0, 1.0), Mat2::Identity()};  // F = U diag(sigma) V^T
  double J = 1.0;
  double psi = 0.0;  // energy density (+inf where a barrier model is inverted)
  Mat2 P = Mat2::Zero();
  // P F^T / J (see above: symmetric but for linear elasticity); zero where J = 0 (undefined).
  Mat2 cauchy = Mat2::Zero();
  Vec2 principal_stress = Vec2::Zero();  // cauchy's (symmetric part's) eigenvalues, larger first
  Mat2 principal_directions = Mat2::Identity();  // unit eigenvectors, columns in that order
  Vec4 eigenvalues = Vec4::Zero();               // of dP/dF, in kEigenvalueNames' order
  Vec4 projected_eigenvalues = Vec4::Zero();     // after clamping the negative ones
  int clamped = 0;                               // how many the projection changed
  bool finite = true;  // false where Psi is +inf (neo-Hookean at J <= 0): no P, no Hessian
};

// Everything above for one F; no finite differences (cheap: one polar SVD, closed forms).
StressAnalysis analyze_stress(Model model, const Mat2& F, const Lame& lame);

// Only what a colouring needs per triangle, without the SVD's vectors or P's eigenvectors.
double energy_density_of(Model model, const Mat2& F, const Lame& lame);
// The principal Cauchy stresses (larger first) and the first one's unit direction, without
// the SVD or trigonometry (the stress glyphs ask for it per triangle every frame); zero
// where J = 0 or a barrier model's energy is infinite.
struct PrincipalStress {
  Vec2 values = Vec2::Zero();
  Vec2 direction = Vec2(1.0, 0.0);
};
PrincipalStress principal_stress_of(Model model, const Mat2& F, const Lame& lame);
// The principal Cauchy stress of largest magnitude, signed (tension > 0); 0 where J <= 0
// for a barrier model.
double signed_max_principal_stress(Model model, const Mat2& F, const Lame& lame);
// The number of dP/dF's four eigenvalues below zero (those the projection clamps).
int clamped_eigenvalue_count(Model model, const Mat2& F, const Lame& lame);

struct FiniteDifferenceErrors {
  // |P - P_fd| / |P_fd| (Frobenius), |P_fd| floored at 1e-4 (mu + |lambda|): the stress of a
  // strain of 1e-4. Below it the differences' own rounding (about 1e-11 of the stiffness)
  // would make the ratio noise over noise (at rest P = 0 exactly and P_fd is rounding).
  double P = 0.0;
  double dPdF = 0.0;  // the same for dP/dF against second differences of Psi
  Mat2 P_fd = Mat2::Zero();
  Mat4 dPdF_fd = Mat4::Zero();  // symmetric, flattened [F11, F21, F12, F22]
};

// Central differences of Psi at F (steps scaled to F and to its smallest singular value,
// so that a barrier model is never evaluated across J = 0), against the model's P and
// unprojected dP/dF. All zero where Psi is +inf at F.
FiniteDifferenceErrors finite_difference_errors(Model model, const Mat2& F, const Lame& lame);
// The same check of any claimed P and dP/dF against any energy density `psi` (the model
// version is this one with the model's functions; a test feeds it a wrong P to see the
// check fail). `barrier`: psi is +inf for J <= 0, so the steps stay inside the smallest
// singular value. `floor` bounds the denominators from below (a stress scale, > 0).
FiniteDifferenceErrors finite_difference_errors(const std::function<double(const Mat2&)>& psi,
                                                const Mat2& P, const Mat4& dPdF, const Mat2& F,
                                                bool barrier, double floor);

// dP/dF, unprojected, as the 4x4 the solver assembles (flattened [F11, F21, F12, F22]).
Mat4 exact_stress_derivative(Model model, const Mat2& F, const Lame& lame);

}  // namespace invfree
