#include "modal/modal_analysis.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "scene/fixed_nodes.h"
#include "scene/scene_mesh.h"

namespace invfree {

namespace {

using Mat3 = Eigen::Matrix3d;

// sigma = D eps with eps = (e_xx, e_yy, 2 e_xy) (engineering shear strain).
Mat3 elasticity_matrix(const Lame& lame) {
  Mat3 d;
  d << lame.lambda + 2 * lame.mu, lame.lambda, 0,  //
      lame.lambda, lame.lambda + 2 * lame.mu, 0,   //
      0, 0, lame.mu;
  return d;
}

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

QuadPairing pair_triangles_into_quads(const std::vector<Vec2>& rest,
                                      const std::vector<std::array<int, 3>>& triangles) {
  QuadPairing out;
  // Each triangle's longest edge, as the local index k of the vertex opposite it; -1 when
  // two edges tie for longest (no diagonal to pair along).
  const int n = static_cast<int>(triangles.size());
  std::vector<int> opposite(n, -1);
  std::map<std::pair<int, int>, std::vector<int>> by_edge;
  for (int t = 0; t < n; ++t) {
    const auto& v = triangles[t];
    double len[3];
    for (int k = 0; k < 3; ++k) len[k] = (rest[v[(k + 2) % 3]] - rest[v[(k + 1) % 3]]).norm();
    const int k = static_cast<int>(std::max_element(len, len + 3) - len);
    const double longest = len[k];
    bool unique = true;
    for (int j = 0; j < 3; ++j)
      if (j != k && len[j] > longest * (1 - 1e-9)) unique = false;
    if (!unique) continue;
    opposite[t] = k;
    const int a = v[(k + 1) % 3], b = v[(k + 2) % 3];
    by_edge[{std::min(a, b), std::max(a, b)}].push_back(t);
  }
  std::vector<int> partner(n, -1);
  for (const auto& [edge, ts] : by_edge)
    if (ts.size() == 2) partner[ts[0]] = ts[1], partner[ts[1]] = ts[0];
  for (int t = 0; t < n; ++t) {
    if (partner[t] < 0) {
      out.quads.clear();
      out.from_triangles.clear();
      out.error = "triangle " + std::to_string(t) +
                  " has no partner sharing its longest edge: quads need the triangles in pairs "
                  "that form the cells of a structured grid";
      return out;
    }
    if (partner[t] < t) continue;
    const auto& v = triangles[t];
    const int k = opposite[t];
    const int a = v[k], b = v[(k + 1) % 3], c = v[(k + 2) % 3];
    const auto& w = triangles[partner[t]];
    const int d = w[opposite[partner[t]]];
    // Counter-clockwise a, b, d, c when (a, b, c) is; the other way round when clockwise.
    std::array<int, 4> q = {a, b, d, c};
    if (cross(rest[b] - rest[a], rest[c] - rest[a]) < 0) q = {a, c, d, b};
    for (int i = 0; i < 4; ++i) {
      const Vec2 e0 = rest[q[(i + 1) % 4]] - rest[q[i]],
                 e1 = rest[q[(i + 2) % 4]] - rest[q[(i + 1) % 4]];
      if (!(cross(e0, e1) > 0)) {
        out.quads.clear();
        out.from_triangles.clear();
        out.error = "triangles " + std::to_string(t) + " and " + std::to_string(partner[t]) +
                    " do not form a convex quadrilateral";
        return out;
      }
    }
    out.quads.push_back(q);
    out.from_triangles.push_back({t, partner[t]});
  }
  return out;
}

ModalModel scene_modal_model(const SceneDef& scene, ModalElement element, std::string* error) {
  ModalModel model;
  model.element = element;
  *error = "";
  if (!scene.has_triangle_elasticity()) {
    *error =
        "the scene has no triangle elasticity (a mass-spring scene): modes needs elastic "
        "triangles";
    return model;
  }
  const Mesh mesh = scene_mesh(scene);
  if (mesh.triangles.empty()) {
    *error = "the scene's mesh has no triangles";
    return model;
  }
  model.rest = mesh.rest;
  model.density = scene.density;
  model.fixed_dofs = select_fixed_dofs(scene, mesh);
  std::vector<Lame> lame = scene_triangle_lame(scene, mesh);
  if (lame.empty()) lame.assign(mesh.triangles.size(), scene.lame);
  if (element == ModalElement::Triangle) {
    model.triangles = mesh.triangles;
    model.lame = std::move(lame);
    return model;
  }
  QuadPairing pairs = pair_triangles_into_quads(mesh.rest, mesh.triangles);
  if (!pairs.error.empty()) {
    *error = "quad elements: " + pairs.error + " (use triangle elements for this mesh)";
    return model;
  }
  for (const auto& [t0, t1] : pairs.from_triangles) {
    if (!(lame[t0] == lame[t1])) {
      *error = "quad elements: triangles " + std::to_string(t0) + " and " + std::to_string(t1) +
               " of one quad have different materials";
      return model;
    }
    model.lame.push_back(lame[t0]);
  }
  model.quads = std::move(pairs.quads);
  return model;
}

Mat6 triangle_stiffness(const std::array<Vec2, 3>& x, const Lame& lame) {
  // Gradients of the barycentric coordinates: constant over the triangle.
  Mat2 dm;
  dm << x[1] - x[0], x[2] - x[0];
  const double area = 0.5 * std::abs(determinant(dm));
  const Mat2 dm_inv = dm.inverse();  // rows: gradients of N1 and N2
  Eigen::Matrix<double, 2, 3> grad;
  grad.col(1) = dm_inv.row(0).transpose();
  grad.col(2) = dm_inv.row(1).transpose();
  grad.col(0) = -grad.col(1) - grad.col(2);
  Eigen::Matrix<double, 3, 6> b = Eigen::Matrix<double, 3, 6>::Zero();
  for (int j = 0; j < 3; ++j) {
    b(0, 2 * j) = grad(0, j);
    b(1, 2 * j + 1) = grad(1, j);
    b(2, 2 * j) = grad(1, j);
    b(2, 2 * j + 1) = grad(0, j);
  }
  return area * b.transpose() * elasticity_matrix(lame) * b;
}

Mat6 triangle_mass(const std::array<Vec2, 3>& x, double density) {
  const double area = 0.5 * std::abs(cross(x[1] - x[0], x[2] - x[0]));
  Mat6 m = Mat6::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 2; ++c)
        m(2 * i + c, 2 * j + c) = density * area / 12.0 * (i == j ? 2 : 1);
  return m;
}

namespace {

// linear.py's 2x2 Gauss rule: points (+-1/sqrt 3, +-1/sqrt 3) in its order, weights 1.
// Calls f(N (4), dN/dx (2x4), detJ) at each point.
template <class F>
void quad_gauss_points(const std::array<Vec2, 4>& x, F&& f) {
  const double gp = 1.0 / std::sqrt(3.0);
  const double points[4][2] = {{-gp, -gp}, {gp, -gp}, {gp, gp}, {-gp, gp}};
  Eigen::Matrix<double, 4, 2> nodes;
  for (int i = 0; i < 4; ++i) nodes.row(i) = x[i].transpose();
  for (const auto& p : points) {
    const double xi = p[0], eta = p[1];
    Eigen::Matrix<double, 2, 4> dn;
    dn << -(1 - eta), (1 - eta), (1 + eta), -(1 + eta),  //
        -(1 - xi), -(1 + xi), (1 + xi), (1 - xi);
    dn *= 0.25;
    const Mat2 jac = dn * nodes;
    const Eigen::Matrix<double, 2, 4> dxy = jac.inverse() * dn;
    Eigen::Matrix<double, 1, 4> n;
    n << (1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta), (1 - xi) * (1 + eta);
    n *= 0.25;
    f(n, dxy, jac.determinant());
  }
}

}  // namespace

Mat8 quad_stiffness(const std::array<Vec2, 4>& x, const Lame& lame) {
  const Mat3 d = elasticity_matrix(lame);
  Mat8 k = Mat8::Zero();
  quad_gauss_points(x, [&](const auto&, const Eigen::Matrix<double, 2, 4>& dxy, double det_j) {
    Eigen::Matrix<double, 3, 8> b = Eigen::Matrix<double, 3, 8>::Zero();
    for (int j = 0; j < 4; ++j) {
      b(0, 2 * j) = dxy(0, j);
      b(1, 2 * j + 1) = dxy(1, j);
      b(2, 2 * j) = dxy(1, j);
      b(2, 2 * j + 1) = dxy(0, j);
    }
    k += b.transpose() * d * b * det_j;
  });
  return k;
}

Mat8 quad_mass(const std::array<Vec2, 4>& x, double density) {
  Mat8 m = Mat8::Zero();
  quad_gauss_points(x, [&](const Eigen::Matrix<double, 1, 4>& n, const auto&, double det_j) {
    Eigen::Matrix<double, 2, 8> nm = Eigen::Matrix<double, 2, 8>::Zero();
    for (int j = 0; j < 4; ++j) nm(0, 2 * j) = nm(1, 2 * j + 1) = n(j);
    m += density * nm.transpose() * nm * det_j;
  });
  return m;
}

ModalMatrices assemble_modal_matrices(const ModalModel& model) {
  const int n = model.dof_count();
  std::vector<Eigen::Triplet<double>> k, m;
  const auto add = [&](const auto& nodes, const auto& ke, const auto& me) {
    const int size = static_cast<int>(nodes.size());
    for (int a = 0; a < size; ++a)
      for (int b = 0; b < size; ++b)
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j) {
            const int r = 2 * nodes[a] + i, c = 2 * nodes[b] + j;
            k.emplace_back(r, c, ke(2 * a + i, 2 * b + j));
            m.emplace_back(r, c, me(2 * a + i, 2 * b + j));
          }
  };
  if (model.element == ModalElement::Triangle) {
    for (size_t e = 0; e < model.triangles.size(); ++e) {
      const auto& t = model.triangles[e];
      const std::array<Vec2, 3> x = {model.rest[t[0]], model.rest[t[1]], model.rest[t[2]]};
      add(t, triangle_stiffness(x, model.lame[e]), triangle_mass(x, model.density));
    }
  } else {
    for (size_t e = 0; e < model.quads.size(); ++e) {
      const auto& q = model.quads[e];
      const std::array<Vec2, 4> x = {model.rest[q[0]], model.rest[q[1]], model.rest[q[2]],
                                     model.rest[q[3]]};
      add(q, quad_stiffness(x, model.lame[e]), quad_mass(x, model.density));
    }
  }
  ModalMatrices out;
  out.K.resize(n, n);
  out.M.resize(n, n);
  out.K.setFromTriplets(k.begin(), k.end());
  out.M.setFromTriplets(m.begin(), m.end());
  return out;
}

ModalResult modal_analysis(const ModalModel& model, int count) {
  ModalResult out;
  const int n = model.dof_count(), free = model.free_dof_count();
  if (count < 1 || count >= free) {
    out.error = "asked for " + std::to_string(count) + " modes of a model with " +
                std::to_string(free) + " free degrees of freedom (1 to " +
                std::to_string(free - 1) + ")";
    return out;
  }
  // The free degrees of freedom and their K and M.
  std::vector<int> reduced(n, 0);
  for (int d : model.fixed_dofs) reduced[d] = -1;
  std::vector<int> free_dofs;
  for (int d = 0; d < n; ++d)
    if (reduced[d] == 0) reduced[d] = static_cast<int>(free_dofs.size()), free_dofs.push_back(d);
  const ModalMatrices full = assemble_modal_matrices(model);
  const auto restrict = [&](const SparseMatrixD& a) {
    std::vector<Eigen::Triplet<double>> entries;
    for (int c = 0; c < a.outerSize(); ++c)
      for (SparseMatrixD::InnerIterator it(a, c); it; ++it)
        if (reduced[it.row()] >= 0 && reduced[it.col()] >= 0)
          entries.emplace_back(reduced[it.row()], reduced[it.col()], it.value());
    SparseMatrixD r(free, free);
    r.setFromTriplets(entries.begin(), entries.end());
    return r;
  };
  const SparseMatrixD k = restrict(full.K), m = restrict(full.M);
  // The shift: below every eigenvalue (rigid modes are 0 and may round to either sign),
  // a billionth of the stiffest degree of freedom's K_ii / M_ii (the top of the spectrum's
  // scale): far below a mesh's lowest elastic mode, far enough from 0 that K - shift M is
  // definite and well conditioned.
  double scale = 0.0;
  for (int i = 0; i < free; ++i) scale = std::max(scale, k.coeff(i, i) / m.coeff(i, i));
  out.shift = -1e-9 * scale;
  const EigenPairs pairs = smallest_eigenpairs(k, &m, count, out.shift);
  if (!pairs.error.empty()) {
    out.error = pairs.error;
    return out;
  }
  out.eigenvalues = pairs.values;
  out.shapes = Eigen::MatrixXd::Zero(n, count);
  for (int j = 0; j < count; ++j) {
    Eigen::Index at = 0;
    pairs.vectors.col(j).cwiseAbs().maxCoeff(&at);
    const double sign = pairs.vectors(at, j) < 0 ? -1.0 : 1.0;
    for (int i = 0; i < free; ++i) out.shapes(free_dofs[i], j) = sign * pairs.vectors(i, j);
  }
  return out;
}

double angular_frequency(double eigenvalue) {
  return eigenvalue > 0 ? std::sqrt(eigenvalue) : 0.0;
}

}  // namespace invfree
