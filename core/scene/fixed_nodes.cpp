#include "scene/fixed_nodes.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace invfree {

namespace {

struct Box {
  Vec2 lo, hi;
};

Box rest_bounds(const Mesh& mesh) {
  Box b{mesh.rest[0], mesh.rest[0]};
  for (const Vec2& p : mesh.rest) {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  return b;
}

// Rest positions are sums of multiples of side / n_seg: compare within a tolerance far
// below the edge length and far above rounding.
double tolerance(const Box& bounds) {
  return 1e-9 * std::max(1.0, (bounds.hi - bounds.lo).maxCoeff());
}

bool near(double a, double b, double tol) {
  return std::abs(a - b) <= tol;
}

bool has_corner(FixedCorners set, FixedCorners corner) {
  return (static_cast<unsigned>(set) & static_cast<unsigned>(corner)) != 0;
}

bool box_is_empty(const SceneDef& s) {
  return (s.fixed_box_min.array() > s.fixed_box_max.array()).any();
}

bool in_box(const SceneDef& s, const Vec2& p, double tol) {
  return in_rest_box(s.fixed_box_min, s.fixed_box_max, p, tol);
}

bool in_extra_box(const Loop& box, const Vec2& p, double tol) {
  return in_rest_box(box[0], box[1], p, tol);
}

bool in_any_extra_box(const SceneDef& s, const Vec2& p, double tol) {
  for (const Loop& box : s.fixed_boxes)
    if (box.size() == 2 && in_extra_box(box, p, tol)) return true;
  return false;
}

bool at_corner(FixedCorners set, const Box& b, const Vec2& p, double tol) {
  const bool left = near(p.x(), b.lo.x(), tol), right = near(p.x(), b.hi.x(), tol);
  const bool bottom = near(p.y(), b.lo.y(), tol), top = near(p.y(), b.hi.y(), tol);
  return (bottom && left && has_corner(set, FixedCorners::BottomLeft)) ||
         (bottom && right && has_corner(set, FixedCorners::BottomRight)) ||
         (top && left && has_corner(set, FixedCorners::TopLeft)) ||
         (top && right && has_corner(set, FixedCorners::TopRight));
}

}  // namespace

double rest_box_tolerance(const Mesh& mesh) {
  return mesh.rest.empty() ? 0.0 : tolerance(rest_bounds(mesh));
}

bool in_rest_box(const Vec2& lo, const Vec2& hi, const Vec2& p, double tol) {
  return (p.array() >= lo.array() - tol).all() && (p.array() <= hi.array() + tol).all();
}

std::vector<int> select_fixed_nodes(const SceneDef& s, const Mesh& mesh) {
  std::vector<int> nodes;
  if (!s.has_fixed || mesh.rest.empty()) return nodes;
  const Box bounds = rest_bounds(mesh);
  const double tol = tolerance(bounds);
  const bool use_box = !box_is_empty(s);
  for (int i = 0; i < mesh.node_count(); ++i) {
    const Vec2& p = mesh.rest[i];
    if (at_corner(s.fixed_corners, bounds, p, tol) || (use_box && in_box(s, p, tol)) ||
        in_any_extra_box(s, p, tol))
      nodes.push_back(i);
  }
  return nodes;
}

std::optional<SceneProblem> fixed_rule_problem(const SceneDef& s, const Mesh& mesh) {
  if (!s.has_fixed || mesh.rest.empty()) return std::nullopt;
  if (!box_is_empty(s)) {
    const double tol = tolerance(rest_bounds(mesh));
    if (std::none_of(mesh.rest.begin(), mesh.rest.end(),
                     [&](const Vec2& p) { return in_box(s, p, tol); })) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "the box [%g, %g] x [%g, %g] holds no node of the rest mesh",
                    s.fixed_box_min.x(), s.fixed_box_max.x(), s.fixed_box_min.y(),
                    s.fixed_box_max.y());
      return SceneProblem{"fixed.box_min", buf, {"fixed.box_max", "mesh.side", "mesh.n_seg"}};
    }
  }
  for (const auto& [key, boxes] :
       {std::pair{"fixed.boxes", &s.fixed_boxes}, std::pair{"fixed.x_boxes", &s.fixed_x_boxes},
        std::pair{"fixed.y_boxes", &s.fixed_y_boxes}})
    for (size_t k = 0; k < boxes->size(); ++k) {
      const Loop& box = (*boxes)[k];
      const std::string which = "box " + std::to_string(k + 1);
      if (box.size() != 2 || !box[0].allFinite() || !box[1].allFinite())
        return SceneProblem{key, which + ": expected [[x_min, y_min], [x_max, y_max]]", {}};
      if ((box[0].array() > box[1].array()).any())
        return SceneProblem{key, which + ": its min corner is above or right of its max", {}};
      const double tol = tolerance(rest_bounds(mesh));
      if (std::none_of(mesh.rest.begin(), mesh.rest.end(),
                       [&](const Vec2& p) { return in_extra_box(box, p, tol); }))
        return SceneProblem{key, which + " holds no node of the rest mesh", {"mesh.shape"}};
    }
  if (select_fixed_dofs(s, mesh).empty())
    return SceneProblem{"fixed.corners",
                        "the [fixed] rules select no node (name corners or give a box)",
                        {"fixed.box_min", "fixed.box_max"}};
  return std::nullopt;
}

}  // namespace invfree

namespace invfree {

std::vector<int> select_fixed_dofs(const SceneDef& s, const Mesh& mesh) {
  std::vector<int> dofs;
  const bool x = s.fixed_components != FixedComponents::Y;
  const bool y = s.fixed_components != FixedComponents::X;
  for (int node : select_fixed_nodes(s, mesh)) {
    if (x) dofs.push_back(2 * node);
    if (y) dofs.push_back(2 * node + 1);
  }
  if (s.has_fixed && !mesh.rest.empty()) {
    const double tol = tolerance(rest_bounds(mesh));
    for (int i = 0; i < mesh.node_count(); ++i) {
      for (const Loop& box : s.fixed_x_boxes)
        if (box.size() == 2 && in_extra_box(box, mesh.rest[i], tol)) dofs.push_back(2 * i);
      for (const Loop& box : s.fixed_y_boxes)
        if (box.size() == 2 && in_extra_box(box, mesh.rest[i], tol)) dofs.push_back(2 * i + 1);
    }
  }
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  return dofs;
}

std::optional<SceneProblem> static_support_problem(const SceneDef& s, const Mesh& mesh) {
  if (!s.is_static()) return std::nullopt;
  // A rigid motion of a body is u_i = (a - t y_i, b + t x_i) about the body's rest centre;
  // each held dof is one linear condition on (a, b, t). The body is held when the
  // conditions have rank 3: the smallest eigenvalue of their normal matrix is not ~0.
  const std::vector<int> dofs = select_fixed_dofs(s, mesh);
  const int bodies = static_cast<int>(mesh.body_begin.size());
  for (int body = 0; body < bodies; ++body) {
    const int begin = mesh.body_begin[body];
    const int end = body + 1 < bodies ? mesh.body_begin[body + 1] : mesh.node_count();
    Vec2 centre = Vec2::Zero();
    double extent = 0.0;
    for (int i = begin; i < end; ++i) centre += mesh.rest[i];
    centre /= double(end - begin);
    for (int i = begin; i < end; ++i) extent = std::max(extent, (mesh.rest[i] - centre).norm());
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    for (int dof : dofs) {
      const int node = dof / 2;
      if (node < begin || node >= end) continue;
      const Vec2 r = (mesh.rest[node] - centre) / extent;  // rotation scaled to length 1
      const Eigen::Vector3d row =
          dof % 2 == 0 ? Eigen::Vector3d(1.0, 0.0, -r.y()) : Eigen::Vector3d(0.0, 1.0, r.x());
      normal += row * row.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(normal);
    if (eig.eigenvalues()[0] > 1e-10 * std::max(1.0, eig.eigenvalues()[2])) continue;
    const Eigen::Vector3d mode = eig.eigenvectors().col(0);
    const char* motion = std::abs(mode[2]) > std::max(std::abs(mode[0]), std::abs(mode[1]))
                             ? "rotate"
                         : std::abs(mode[0]) >= std::abs(mode[1]) ? "move in x"
                                                                  : "move in y";
    const std::string which = bodies > 1 ? "[[body]] " + std::to_string(body + 1) : "the body";
    return SceneProblem{
        "solver.integrator",
        "static equilibrium needs every body held against rigid motion, but " + which +
            " is free to " + motion +
            " (hold nodes with [fixed]; a plane alone does not hold a body)",
        {"fixed.enabled", "fixed.corners", "fixed.box_min", "fixed.boxes", "fixed.components"}};
  }
  return std::nullopt;
}

}  // namespace invfree
