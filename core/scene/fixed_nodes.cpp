#include "scene/fixed_nodes.h"

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
  return (p.array() >= s.fixed_box_min.array() - tol).all() &&
         (p.array() <= s.fixed_box_max.array() + tol).all();
}

bool in_extra_box(const Loop& box, const Vec2& p, double tol) {
  return (p.array() >= box[0].array() - tol).all() && (p.array() <= box[1].array() + tol).all();
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
  for (size_t k = 0; k < s.fixed_boxes.size(); ++k) {
    const Loop& box = s.fixed_boxes[k];
    const std::string which = "box " + std::to_string(k + 1);
    if (box.size() != 2 || !box[0].allFinite() || !box[1].allFinite())
      return SceneProblem{"fixed.boxes", which + ": expected [[x_min, y_min], [x_max, y_max]]", {}};
    if ((box[0].array() > box[1].array()).any())
      return SceneProblem{
          "fixed.boxes", which + ": its min corner is above or right of its max", {}};
    const double tol = tolerance(rest_bounds(mesh));
    if (std::none_of(mesh.rest.begin(), mesh.rest.end(),
                     [&](const Vec2& p) { return in_extra_box(box, p, tol); }))
      return SceneProblem{"fixed.boxes", which + " holds no node of the rest mesh", {"mesh.shape"}};
  }
  if (select_fixed_nodes(s, mesh).empty())
    return SceneProblem{"fixed.corners",
                        "the [fixed] rules select no node (name corners or give a box)",
                        {"fixed.box_min", "fixed.box_max"}};
  return std::nullopt;
}

}  // namespace invfree
