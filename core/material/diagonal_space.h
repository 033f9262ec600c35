// The stress derivative dP/dF of an isotropic energy assembled from diagonal-space
// quantities (lecture 9, "Diagonal Space Derivatives"; Smith et al. 2019, "Analytic
// Eigensystems for Isotropic Distortion Energies", for the eigenvector form used here).
//
// With F = U diag(s) V^T (polar SVD), dP/dF is block diagonal in the basis
//   D1 = u1 v1^T, D2 = u2 v2^T            -> the A block, A_ij = d2Psi/ds_i ds_j
//   flip  = (u1 v2^T + u2 v1^T)/sqrt(2)   -> eigenvalue (Psi_1 - Psi_2)/(s1 - s2) = 2 B_left
//   twist = (u2 v1^T - u1 v2^T)/sqrt(2)   -> eigenvalue (Psi_1 + Psi_2)/(s1 + s2) = 2 B_right
// Each model supplies the flip and twist eigenvalues in closed form, so the divisions by
// s1 - s2 and s1 + s2 never happen numerically (no loss near s1 = s2 or small s).
// Projecting to PSD clamps A's eigenvalues and the two scalars at zero.
#pragma once

#include "material/polar_svd.h"
#include "material/psd_projection.h"
#include "types.h"

namespace invfree {

struct DiagonalHessian {
  Mat2 A;        // d2 Psi_hat / d sigma^2
  double flip;   // (Psi_1 - Psi_2) / (sigma_1 - sigma_2)
  double twist;  // (Psi_1 + Psi_2) / (sigma_1 + sigma_2)
};

inline Mat4 compose_stress_derivative(const PolarSvd& svd, const DiagonalHessian& d,
                                      bool project_to_psd) {
  const Mat2 A = project_to_psd ? project_psd(d.A) : d.A;
  const double flip = project_to_psd ? std::max(d.flip, 0.0) : d.flip;
  const double twist = project_to_psd ? std::max(d.twist, 0.0) : d.twist;
  const Vec2 u1 = svd.U.col(0), u2 = svd.U.col(1), v1 = svd.V.col(0), v2 = svd.V.col(1);
  const Vec4 d1 = flatten(u1 * v1.transpose());
  const Vec4 d2 = flatten(u2 * v2.transpose());
  const Vec4 a12 = flatten(u1 * v2.transpose());
  const Vec4 a21 = flatten(u2 * v1.transpose());
  const double inv_sqrt2 = 0.70710678118654752440;
  const Vec4 l = inv_sqrt2 * (a12 + a21);
  const Vec4 t = inv_sqrt2 * (a21 - a12);
  return A(0, 0) * d1 * d1.transpose() + A(1, 1) * d2 * d2.transpose() +
         A(0, 1) * (d1 * d2.transpose() + d2 * d1.transpose()) + flip * l * l.transpose() +
         twist * t * t.transpose();
}

}  // namespace invfree
