#include "scene/reduced_basis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "linalg/eigenpairs.h"
#include "material/models.h"
#include "material/triangle_elasticity.h"
#include "scene/scene_mesh.h"

namespace invfree {

namespace {

int monomial_count(int order) {
  return (order + 1) * (order + 2) / 2;
}

// The monomials X^a Y^b, a + b <= order, by degree and then falling powers of X (the
// tutorial's order: 1, X, Y, X^2, XY, Y^2, X^3, X^2 Y, X Y^2, Y^3).
void monomials(const Vec2& p, int order, double* out) {
  int k = 0;
  for (int degree = 0; degree <= order; ++degree)
    for (int b = 0; b <= degree; ++b) out[k++] = std::pow(p.x(), degree - b) * std::pow(p.y(), b);
}

Eigen::MatrixXd polynomial_basis(const Mesh& mesh, int order) {
  const int bodies = static_cast<int>(mesh.body_begin.size());
  const int per_dim = monomial_count(order);
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(2 * mesh.node_count(), bodies * 2 * per_dim);
  std::vector<double> m(per_dim);
  for (int k = 0; k < bodies; ++k) {
    const int begin = mesh.body_begin[k];
    const int end = k + 1 < bodies ? mesh.body_begin[k + 1] : mesh.node_count();
    Eigen::AlignedBox2d box;
    for (int i = begin; i < end; ++i) box.extend(mesh.rest[i]);
    const Vec2 centre = box.center();
    const double scale = std::max(0.5 * box.sizes().maxCoeff(), 1e-300);
    for (int i = begin; i < end; ++i) {
      monomials((mesh.rest[i] - centre) / scale, order, m.data());
      for (int d = 0; d < 2; ++d)
        for (int j = 0; j < per_dim; ++j) B(2 * i + d, (2 * k + d) * per_dim + j) = m[j];
    }
  }
  return B;
}

// The shift for the modal eigen-solve: below the smallest eigenvalue (0, the rigid modes)
// by a small fraction of the typical diagonal entry, so that H - shift I factorises.
double modal_shift(const Eigen::SparseMatrix<double>& H) {
  const double mean_diagonal = H.diagonal().cwiseAbs().mean();
  return -1e-6 * std::max(mean_diagonal, std::numeric_limits<double>::min());
}

// Equal to solver precision: the pair's gap is below 1e-8 of the spectrum's scale.
bool degenerate(double a, double b, double scale) {
  return std::abs(b - a) <= 1e-8 * scale;
}

}  // namespace

int polynomial_basis_size(int order, int bodies) {
  return bodies * 2 * monomial_count(order);
}

Eigen::SparseMatrix<double> rest_elastic_hessian(const SceneDef& scene, const Mesh& mesh) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(36 * static_cast<size_t>(mesh.triangle_count()));
  const std::vector<Lame> own = scene_triangle_lame(scene, mesh);  // empty: one material
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Lame& lame = own.empty() ? scene.lame : own[t];
    const Mat4 dPdF = stress_derivative(scene.model, Mat2::Identity(), lame, false);
    const Mat46 J = deformation_gradient_jacobian(mesh.rest_shape_inverse[t]);
    const Mat6 H = mesh.rest_area[t] * J.transpose() * dPdF * J;
    const auto& tri = mesh.triangles[t];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 2; ++i)
        for (int b = 0; b < 3; ++b)
          for (int j = 0; j < 2; ++j)
            entries.emplace_back(2 * tri[a] + i, 2 * tri[b] + j, H(2 * a + i, 2 * b + j));
  }
  Eigen::SparseMatrix<double> H(2 * mesh.node_count(), 2 * mesh.node_count());
  H.setFromTriplets(entries.begin(), entries.end());
  return H;
}

ReducedBasisBuild build_reduced_basis(const SceneDef& scene, const Mesh& mesh) {
  ReducedBasisBuild out;
  const int dofs = 2 * mesh.node_count();
  switch (scene.reduced_basis) {
    case ReducedBasis::Full:
      return out;
    case ReducedBasis::Polynomial: {
      const int r =
          polynomial_basis_size(scene.reduced_order, static_cast<int>(mesh.body_begin.size()));
      if (r > dofs) {
        out.error = "reduced.order: the order-" + std::to_string(scene.reduced_order) +
                    " basis has " + std::to_string(r) + " columns, more than the mesh's " +
                    std::to_string(dofs) + " unknowns";
        return out;
      }
      out.basis = polynomial_basis(mesh, scene.reduced_order);
      return out;
    }
    case ReducedBasis::Modal: {
      const int count = scene.reduced_modes;
      if (count + 1 >= dofs) {
        out.error = "reduced.modes: " + std::to_string(count) + " modes of a mesh with " +
                    std::to_string(dofs) + " unknowns (at most " + std::to_string(dofs - 2) + ")";
        return out;
      }
      const Eigen::SparseMatrix<double> H = rest_elastic_hessian(scene, mesh);
      // One more pair than asked for: the cut must not split a degenerate group.
      const EigenPairs pairs = smallest_eigenpairs(H, nullptr, count + 1, modal_shift(H));
      if (!pairs.error.empty()) {
        out.error = "reduced.modes: " + pairs.error;
        return out;
      }
      const double scale =
          std::max(std::abs(pairs.values[count]), H.diagonal().cwiseAbs().maxCoeff());
      if (degenerate(pairs.values[count - 1], pairs.values[count], scale)) {
        int below = count - 1;
        while (below > 0 && degenerate(pairs.values[below - 1], pairs.values[count - 1], scale))
          --below;
        char values[96];
        std::snprintf(values, sizeof values, "%.6g and %.6g", pairs.values[count - 1],
                      pairs.values[count]);
        out.error = "reduced.modes: " + std::to_string(count) +
                    " splits a degenerate group of eigenvalues (modes " + std::to_string(count) +
                    " and " + std::to_string(count + 1) + ": " + values + "); use " +
                    (below > 0 ? std::to_string(below) + " or more than " : "more than ") +
                    std::to_string(count);
        return out;
      }
      out.basis = pairs.vectors.leftCols(count);
      out.eigenvalues = pairs.values;
      return out;
    }
  }
  return out;
}

std::optional<SceneProblem> reduced_basis_problem(const SceneDef& s, const Mesh& mesh) {
  if (s.reduced_basis == ReducedBasis::Full) return std::nullopt;
  const char* why = nullptr;
  std::string cause;
  if (s.has_ceiling)
    why = "a reduced basis has no ceiling unknown: remove [ceiling]", cause = "ceiling.enabled";
  else if (s.has_fixed)
    why = "a reduced basis cannot hold nodes fixed: remove [fixed]", cause = "fixed.corners";
  else if (s.is_static())
    why = "a reduced basis runs the dynamic integrator only", cause = "solver.integrator";
  else if (s.integrator == Integrator::SymplecticEuler)
    why = "symplectic Euler has no Newton step to reduce", cause = "solver.integrator";
  else if (s.linear_solver != LinearSolverKind::Auto)
    why = "a reduced basis solves its dense r x r system directly: leave solver.linear_solver auto",
    cause = "solver.linear_solver";
  else if (s.reduced_basis == ReducedBasis::Modal && !s.has_triangle_elasticity())
    why = "the modal basis comes from the triangles' elasticity, which a mass-spring scene has not",
    cause = "mass_spring.enabled";
  if (why) return SceneProblem{"reduced.basis", why, {cause}};
  const ReducedBasisBuild build = build_reduced_basis(s, mesh);
  if (!build.error.empty()) {
    const auto colon = build.error.find(": ");
    return SceneProblem{
        build.error.substr(0, colon), build.error.substr(colon + 2), {"reduced.basis"}};
  }
  return std::nullopt;
}

std::optional<std::array<Vec2, 3>> affine_anchor_triangle(const SceneDef& scene, const Mesh& mesh,
                                                          const VecX& x) {
  if (scene.reduced_basis != ReducedBasis::Polynomial || scene.reduced_order != 1 ||
      mesh.body_begin.size() != 1 || mesh.node_count() < 3)
    return std::nullopt;
  // The tutorial's anchors: from the rest shape's mean and bounding box.
  Vec2 mean = Vec2::Zero();
  Eigen::AlignedBox2d box;
  for (const Vec2& p : mesh.rest) mean += p, box.extend(p);
  mean /= mesh.node_count();
  const double scale = box.diagonal().norm() / std::sqrt(2.0);
  const Vec2 c = mean - Vec2::Constant(scale / 3.0);
  const std::array<Vec2, 3> rest = {c, c + Vec2(scale, 0.0), c + Vec2(0.0, scale)};
  // The best-fit affine map x = a + M X, per coordinate: least squares on [1 X Y].
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, 2> rhs = Eigen::Matrix<double, 3, 2>::Zero();
  for (int i = 0; i < mesh.node_count(); ++i) {
    const Eigen::Vector3d row(1.0, mesh.rest[i].x(), mesh.rest[i].y());
    normal += row * row.transpose();
    rhs += row * x.segment<2>(2 * i).transpose();
  }
  const Eigen::Matrix<double, 3, 2> map = normal.ldlt().solve(rhs);
  std::array<Vec2, 3> anchors;
  for (int k = 0; k < 3; ++k)
    anchors[k] = (Eigen::RowVector3d(1.0, rest[k].x(), rest[k].y()) * map).transpose();
  return anchors;
}

}  // namespace invfree
