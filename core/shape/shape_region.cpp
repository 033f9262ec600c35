// Shape -> region (shape_region.h): the analytic shapes' loops, the polygon's outline and
// holes oriented, and the svg's loops filtered through their nesting tree and fill rule.
#include "shape/shape_region.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "shape/polygon_checks.h"

namespace invfree {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool positive_length(double v) {
  return std::isfinite(v) && v > 0;
}

std::string check_length(double v, const char* key) {
  if (!positive_length(v)) return std::string(key) + ": must be finite and > 0";
  return "";
}

Loop oriented(const Loop& loop, bool ccw) {
  Loop out = loop;
  if ((loop_signed_area(out) > 0) != ccw) std::reverse(out.begin(), out.end());
  return out;
}

// A circle as a regular n-gon, n a multiple of 4 (circle_segments), its points at the odd
// multiples of pi / n: a flat side at the bottom, so a disk rests on the ground instead of
// balancing on a point, and mirror symmetry about both axes, exact (every quadrant mirrors
// the first one's points).
Loop circle(double r, int n, bool ccw) {
  const int q = n / 4;
  std::vector<Vec2> first(q);
  for (int k = 0; k < q; ++k) {
    const double t = std::numbers::pi * (2 * k + 1) / n;
    first[k] = Vec2(r * std::cos(t), r * std::sin(t));
  }
  Loop loop;
  loop.reserve(n);
  for (int k = 0; k < q; ++k) loop.push_back(first[k]);
  for (int k = q - 1; k >= 0; --k) loop.push_back(Vec2(-first[k].x(), first[k].y()));
  for (int k = 0; k < q; ++k) loop.push_back(Vec2(-first[k].x(), -first[k].y()));
  for (int k = q - 1; k >= 0; --k) loop.push_back(Vec2(first[k].x(), -first[k].y()));
  if (!ccw) std::reverse(loop.begin(), loop.end());
  return loop;
}

std::vector<std::string> path_names(std::size_t count) {
  std::vector<std::string> names;
  for (std::size_t k = 0; k < count; ++k) names.push_back("paths[" + std::to_string(k) + "]");
  return names;
}

bool filled(int winding, FillRule rule) {
  return rule == FillRule::NonZero ? winding != 0 : (winding % 2) != 0;
}

// The svg's loops (validated pairwise disjoint) kept where the fill changes across them.
std::vector<RegionLoop> svg_region(const ShapeFile& file) {
  const std::vector<Loop>& loops = file.loops;
  const int n = static_cast<int>(loops.size());
  std::vector<double> area(n);
  std::vector<Eigen::AlignedBox2d> box(n);
  for (int i = 0; i < n; ++i) {
    area[i] = loop_signed_area(loops[i]);
    for (const Vec2& p : loops[i]) box[i].extend(p);
  }
  // Parent: the smallest loop holding this one's first point (disjoint loops nest).
  std::vector<int> parent(n, -1);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (j != i && box[j].contains(loops[i][0]) &&
          (parent[i] < 0 || std::abs(area[j]) < std::abs(area[parent[i]])) &&
          point_in_loop(loops[i][0], loops[j]) > 0)
        parent[i] = j;
  // Windings just inside each loop, parents first (a parent's area is the larger).
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return std::abs(area[a]) > std::abs(area[b]); });
  std::vector<int> inside(n, 0);
  for (int i : order) inside[i] = (parent[i] >= 0 ? inside[parent[i]] : 0) + (area[i] > 0 ? 1 : -1);
  std::vector<RegionLoop> region;
  for (int i = 0; i < n; ++i) {
    const bool in = filled(inside[i], file.fill_rule);
    const bool out = filled(parent[i] >= 0 ? inside[parent[i]] : 0, file.fill_rule);
    if (in != out) region.push_back({oriented(loops[i], in), !in});
  }
  return region;
}

double region_signed_area(const std::vector<RegionLoop>& loops) {
  double a = 0;
  for (const RegionLoop& l : loops) a += loop_signed_area(l.points);
  return a;
}

}  // namespace

int circle_segments(double r, double max_edge) {
  // A chord of n segments is 2 r sin(pi/n) < 2 pi r / n <= max_edge; n rounded up to a
  // multiple of 4 for circle()'s symmetry.
  const double n = std::ceil(2 * std::numbers::pi * r / max_edge);
  if (!(n < 1e8)) return 100'000'000;  // refused by the triangle cap before it is built
  return (std::max(12, static_cast<int>(n)) + 3) / 4 * 4;
}

std::string validate_shape(const ShapeDef& shape) {
  switch (shape.kind) {
    case ShapeKind::Rectangle:
      if (std::string r = check_length(shape.width, "width"); !r.empty()) return r;
      return check_length(shape.height, "height");
    case ShapeKind::Disk:
      return check_length(shape.radius, "radius");
    case ShapeKind::Ring:
      if (std::string r = check_length(shape.radius, "radius"); !r.empty()) return r;
      if (std::string r = check_length(shape.inner_radius, "inner_radius"); !r.empty()) return r;
      if (!(shape.inner_radius < shape.radius)) return "inner_radius: must be < radius";
      return "";
    case ShapeKind::Polygon:
      return check_polygon_with_holes(shape.outline, shape.holes);
    case ShapeKind::Svg: {
      if (shape.loaded.loops.empty()) return "file: no closed path is filled";
      const std::vector<std::string> names = path_names(shape.loaded.loops.size());
      if (std::string r = check_disjoint_loops(shape.loaded.loops, names); !r.empty())
        return "file: " + r;
      return "";
    }
    case ShapeKind::Points:
      if (shape.points.empty()) return "points: shape \"points\" needs at least one point";
      for (size_t k = 0; k < shape.points.size(); ++k)
        if (!shape.points[k].allFinite())
          return "points: point " + std::to_string(k) + " must be finite";
      return "";
    case ShapeKind::Square:
    case ShapeKind::MeshFile:
      return "";
  }
  return "shape: unknown kind";
}

ShapeRegion shape_region(const ShapeDef& shape, double max_edge) {
  ShapeRegion region;
  if (shape.kind == ShapeKind::Square || shape.kind == ShapeKind::MeshFile ||
      shape.kind == ShapeKind::Points) {
    region.error =
        std::string("shape: ") + enum_name(kShapeKindNames, shape.kind) + " has no outline to mesh";
    return region;
  }
  region.error = validate_shape(shape);
  if (!region.error.empty()) return region;
  const bool curved = shape.kind == ShapeKind::Disk || shape.kind == ShapeKind::Ring;
  if (curved && !positive_length(max_edge)) {
    region.error = "max_edge: must be finite and > 0";
    return region;
  }
  switch (shape.kind) {
    case ShapeKind::Rectangle: {
      const double x = shape.width / 2, y = shape.height / 2;
      region.loops.push_back({{Vec2(-x, -y), Vec2(x, -y), Vec2(x, y), Vec2(-x, y)}, false});
      break;
    }
    case ShapeKind::Disk:
      region.loops.push_back(
          {circle(shape.radius, circle_segments(shape.radius, max_edge), true), false});
      break;
    case ShapeKind::Ring:
      region.loops.push_back(
          {circle(shape.radius, circle_segments(shape.radius, max_edge), true), false});
      region.loops.push_back(
          {circle(shape.inner_radius, circle_segments(shape.inner_radius, max_edge), false), true});
      break;
    case ShapeKind::Polygon:
      region.loops.push_back({oriented(shape.outline, true), false});
      for (const Loop& hole : shape.holes) region.loops.push_back({oriented(hole, false), true});
      break;
    case ShapeKind::Svg:
      region.loops = svg_region(shape.loaded);
      if (region.loops.empty()) region.error = "file: no closed path is filled";
      break;
    default:
      break;
  }
  return region;
}

double region_area_error_bound(const ShapeDef& shape, double max_edge) {
  auto shortfall = [&](double r) {
    const double x = 2 * std::numbers::pi / circle_segments(r, max_edge);
    return std::numbers::pi * r * r * x * x / 6;
  };
  if (shape.kind == ShapeKind::Disk) return shortfall(shape.radius);
  if (shape.kind == ShapeKind::Ring) return shortfall(shape.radius) + shortfall(shape.inner_radius);
  return 0.0;
}

Eigen::AlignedBox2d shape_bounds(const ShapeDef& shape) {
  Eigen::AlignedBox2d box;
  switch (shape.kind) {
    case ShapeKind::Square:
      break;
    case ShapeKind::Rectangle:
      box.extend(Vec2(-shape.width / 2, -shape.height / 2));
      box.extend(Vec2(shape.width / 2, shape.height / 2));
      break;
    case ShapeKind::Disk:
    case ShapeKind::Ring:
      box.extend(Vec2(-shape.radius, -shape.radius));
      box.extend(Vec2(shape.radius, shape.radius));
      break;
    case ShapeKind::Polygon:
      for (const Vec2& p : shape.outline) box.extend(p);
      break;
    case ShapeKind::Svg:
      for (const Loop& loop : shape.loaded.loops)
        for (const Vec2& p : loop) box.extend(p);
      break;
    case ShapeKind::MeshFile:
      for (const Vec2& p : shape.loaded.nodes) box.extend(p);
      break;
    case ShapeKind::Points:
      for (const Vec2& p : shape.points) box.extend(p);
      break;
  }
  return box;
}

double shape_max_edge(const ShapeDef& shape, int n_seg) {
  if (shape.max_edge > 0) return shape.max_edge;
  const Eigen::AlignedBox2d box = shape_bounds(shape);
  if (box.isEmpty() || n_seg <= 0) return kNaN;
  return box.sizes().maxCoeff() / n_seg;
}

double shape_area(const ShapeDef& shape) {
  if (shape.kind == ShapeKind::Square) return kNaN;
  if (shape.kind == ShapeKind::Points) return 0.0;  // particles: no triangles, no area
  if (shape.kind == ShapeKind::MeshFile) {
    double a = 0;
    const auto& nodes = shape.loaded.nodes;
    for (const auto& t : shape.loaded.triangles) {
      for (int v : t)
        if (v < 0 || v >= static_cast<int>(nodes.size())) return kNaN;
      const Vec2 u = nodes[t[1]] - nodes[t[0]], v = nodes[t[2]] - nodes[t[0]];
      a += 0.5 * std::abs(u.x() * v.y() - u.y() * v.x());
    }
    return a;
  }
  if (!validate_shape(shape).empty()) return kNaN;
  switch (shape.kind) {
    case ShapeKind::Rectangle:
      return shape.width * shape.height;
    case ShapeKind::Disk:
      return std::numbers::pi * shape.radius * shape.radius;
    case ShapeKind::Ring:
      return std::numbers::pi *
             (shape.radius * shape.radius - shape.inner_radius * shape.inner_radius);
    default:
      // Polygons: the loops' areas do not depend on max_edge.
      return region_signed_area(shape_region(shape, 1.0).loops);
  }
}

}  // namespace invfree
