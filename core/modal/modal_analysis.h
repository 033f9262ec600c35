// Linear modal analysis (the course's chapter 9, `9_reduced_DOF/linear.py`): the smallest
// eigenpairs of K phi = lambda M phi, K the small-strain (linear elasticity) stiffness and M
// the consistent mass matrix of a scene's rest mesh, with the scene's [fixed] degrees of
// freedom eliminated. lambda = omega^2 (1/s^2); omega the angular frequency (rad/s).
//
// Two elements over the same nodes:
//  - Triangle: P1 (linear) triangles, the scene's own mesh, any shape. Constant strain per
//    triangle; consistent mass rho A / 12 (1 + delta_ij) per component.
//  - Quad: 4-node bilinear quads with 2x2 Gauss quadrature for K and M, as linear.py. The
//    quads are the mesh's triangles taken in pairs: two triangles that share their longest
//    edge (the diagonal of a structured grid's cell) and together form a strictly convex
//    quadrilateral. A mesh that does not pair up entirely (CGAL-meshed shapes) is refused.
// Material: sigma = 2 mu eps + lambda tr(eps) I with each element's Lame parameters, the
// 2D (plane strain) law invfree simulates; plane stress is the same law with
// lambda* = 2 mu lambda / (lambda + 2 mu) (a scene gives mu and lambda* then). The model
// (neo-Hookean, stable neo-Hookean, linear) only matters away from rest: each of them has
// this K as its Hessian at the rest shape.
// Units: the 2D model is per metre of thickness: density kg/m^2, mu and lambda Pa. A slab
// of thickness t scales K and M alike, so t cancels in lambda; the density does not
// (lambda scales as stiffness / density).
// Eigenpairs by Spectra's shift-and-invert Lanczos (linalg/eigenpairs.h) with a small
// negative shift, so that a body with free rigid motions (3 modes at lambda = 0) works.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "enum_names.h"
#include "linalg/eigenpairs.h"
#include "material/material.h"
#include "scene/scene.h"
#include "types.h"

namespace invfree {

// ModalElement and its names: scene/scene.h ([modes] element).

// What the analysis discretises: rest nodes, elements (triangles or counter-clockwise
// quads), each element's Lame parameters, the density and the held degrees of freedom
// (2 node + component, ascending).
struct ModalModel {
  ModalElement element = ModalElement::Triangle;
  std::vector<Vec2> rest;
  std::vector<std::array<int, 3>> triangles;  // ModalElement::Triangle
  std::vector<std::array<int, 4>> quads;      // ModalElement::Quad
  std::vector<Lame> lame;                     // per element
  double density = 1.0;                       // kg/m^2
  std::vector<int> fixed_dofs;
  int dof_count() const { return 2 * static_cast<int>(rest.size()); }
  int free_dof_count() const { return dof_count() - static_cast<int>(fixed_dofs.size()); }
};

// The quads of a mesh whose triangles pair up (see the top); on failure `error` names a
// triangle that has no partner.
struct QuadPairing {
  std::vector<std::array<int, 4>> quads;           // counter-clockwise
  std::vector<std::array<int, 2>> from_triangles;  // the two triangles of each quad
  std::string error;
};
QuadPairing pair_triangles_into_quads(const std::vector<Vec2>& rest,
                                      const std::vector<std::array<int, 3>>& triangles);

// A validated scene's model: its mesh (every body), each triangle's material, its density
// and its [fixed] degrees of freedom. "" or why not into *error (no triangle elasticity: a
// mass-spring or particle scene; quads that do not pair up; a body's two triangles of one
// quad with different materials).
ModalModel scene_modal_model(const SceneDef& scene, ModalElement element, std::string* error);

// Element matrices, degrees of freedom ordered x0, y0, x1, y1, ...
Mat6 triangle_stiffness(const std::array<Vec2, 3>& x, const Lame& lame);
Mat6 triangle_mass(const std::array<Vec2, 3>& x, double density);
using Mat8 = Eigen::Matrix<double, 8, 8>;
Mat8 quad_stiffness(const std::array<Vec2, 4>& x, const Lame& lame);
Mat8 quad_mass(const std::array<Vec2, 4>& x, double density);

// The assembled K and M over every degree of freedom (2N x 2N), fixed ones included.
struct ModalMatrices {
  SparseMatrixD K, M;
};
ModalMatrices assemble_modal_matrices(const ModalModel& model);

struct ModalResult {
  VecX eigenvalues;        // ascending, 1/s^2 (rigid modes: about 0, either sign)
  Eigen::MatrixXd shapes;  // 2N x count: M-orthonormal over the free dofs, 0 at fixed ones;
                           // each column's largest-magnitude entry positive
  double shift = 0.0;      // the shift used
  std::string error;       // "" or why not (count out of range, no convergence)
};

// The `count` smallest modes (1 <= count < free_dof_count()).
ModalResult modal_analysis(const ModalModel& model, int count);

// omega = sqrt(lambda) (rad/s), 0 for lambda <= 0 (a rigid mode's rounding); f = omega/2pi.
double angular_frequency(double eigenvalue);

}  // namespace invfree
