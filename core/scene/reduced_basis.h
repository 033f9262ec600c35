// The reduced basis of a scene's [reduced] section (the course's chapter 9): Newton's steps
// restricted to a subspace, so that x stays x^0 + B q. B is dense, 2N x r, built once per
// mesh:
//  - polynomial, order k (1 affine, 2 quadratic, 3 cubic): per body and per coordinate, the
//    monomials of the rest position up to degree k (1, X, Y, X^2, XY, Y^2, X^3, ...), the
//    tutorial's utils.compute_reduced_basis. They are taken in the body's own centred,
//    scaled coordinates ((X - c) / s), which span the same space as the tutorial's raw
//    monomials (a polynomial space of degree k is invariant under translation and scaling)
//    and keep B^T H B well conditioned for a body far from the origin.
//  - modal: the eigenvectors of the `modes` smallest eigenvalues of the elastic energy's
//    Hessian at rest, unprojected (for every model, the linear-elastic stiffness of the
//    mesh; its rigid modes, eigenvalue 0, come first). From Spectra's shift-and-invert
//    Lanczos (linalg/eigenpairs.h). A count that splits a degenerate group of eigenvalues
//    (mode `modes` and the next equal to solver precision) is refused: its subspace is not
//    defined by the scene, only by the solver's rounding.
// What the reduction costs (docs/method.md, "Reduced bases"): the gradient and Hessian are
// still assembled over the full mesh (O(N)), then B^T g and B^T (H B) (O(nnz(H) r + N r^2)),
// and the r x r system is solved densely (O(r^3)) instead of the sparse factorisation of H;
// the line search, the filters and the invariants stay in full space.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <array>
#include <optional>
#include <string>

#include "scene/mesh.h"
#include "scene/scene.h"

namespace invfree {

struct ReducedBasisBuild {
  Eigen::MatrixXd basis;  // 2N x r; empty for the full basis
  VecX eigenvalues;       // modal: the modes' eigenvalues (ascending) and the next one
  std::string error;      // "" or why the basis cannot be built ("reduced.modes: ...")
};

ReducedBasisBuild build_reduced_basis(const SceneDef& scene, const Mesh& mesh);

// The number of columns of the scene's polynomial basis: bodies * 2 * (monomials of
// degree <= order).
int polynomial_basis_size(int order, int bodies);

// The unprojected Hessian of the elastic energy at the rest shape (both triangles stored).
Eigen::SparseMatrix<double> rest_elastic_hessian(const SceneDef& scene, const Mesh& mesh);

// What keeps the scene's [reduced] section from running, or nullopt (scene checks).
std::optional<SceneProblem> reduced_basis_problem(const SceneDef& scene, const Mesh& mesh);

// The affine basis's anchor triangle (the start of affine body dynamics, as the tutorial
// draws it): three anchors around the rest shape (its centre less a third of `scale`, and
// that point moved by `scale` in x and in y; scale = the rest bounding box's diagonal / sqrt 2),
// carried by the affine map that best fits positions x (least squares over the nodes).
// nullopt unless the scene's basis is polynomial of order 1 with one body.
std::optional<std::array<Vec2, 3>> affine_anchor_triangle(const SceneDef& scene, const Mesh& mesh,
                                                          const VecX& x);

}  // namespace invfree
