// mesh_shape (shape_mesh.h): validate, refuse too large a mesh, mesh, and keep the last
// few results in a small cache guarded by a mutex (meshing itself runs outside the lock,
// so two threads meshing different shapes do not wait for each other).
#include "shape/shape_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <mutex>
#include <numbers>

#include "shape/mesh_check.h"
#include "shape/shape_region.h"
#include "shape/triangulate.h"

namespace invfree {
namespace {

constexpr std::size_t kCacheSize = 4;

struct CacheEntry {
  ShapeDef shape;
  double max_edge;
  ShapeMeshResult result;
};

std::mutex cache_mutex;
std::deque<CacheEntry> cache;  // most recent first

// The key naming the geometry a meshing failure comes from.
const char* geometry_key(const ShapeDef& shape) {
  switch (shape.kind) {
    case ShapeKind::Polygon:
      return "outline";
    case ShapeKind::Svg:
    case ShapeKind::MeshFile:
      return "file";
    case ShapeKind::Points:
      return "points";
    default:
      return "max_edge";
  }
}

std::string format_count(double v) {
  char buf[400];
  std::snprintf(buf, sizeof buf, "%.0f", v);
  std::string s = buf, out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (i > 0 && (s.size() - i) % 3 == 0) out += ',';
    out += s[i];
  }
  return out;
}

// An estimate shown as what it is: two significant digits (39,903,586,013 -> 40,000,000,000).
double two_digits(double v) {
  if (!(v >= 100) || !std::isfinite(v)) return v;
  const double unit = std::pow(10.0, std::floor(std::log10(v)) - 1);
  return std::round(v / unit) * unit;
}

ShapeMeshResult mesh_uncached(const ShapeDef& shape, double max_edge) {
  ShapeMeshResult out;
  if (shape.kind == ShapeKind::Square) {
    out.error = "shape: the square is meshed by square_mesh (scene/mesh.h), not mesh_shape";
    return out;
  }
  if (shape.kind == ShapeKind::MeshFile) {
    CheckedMesh checked = check_mesh(shape.loaded);
    if (!checked.error.empty()) {
      out.error = checked.error;
      return out;
    }
    out.mesh.rest = std::move(checked.nodes);
    out.mesh.triangles = std::move(checked.triangles);
    compute_rest_data(out.mesh);
    return out;
  }
  if (std::string r = validate_shape(shape); !r.empty()) {
    out.error = r;
    return out;
  }
  if (shape.kind == ShapeKind::Points) {  // particles: nodes only, no triangles
    out.mesh.rest = shape.points;
    compute_rest_data(out.mesh);
    return out;
  }
  if (!(std::isfinite(max_edge) && max_edge > 0)) {
    out.error = "max_edge: must be finite and > 0";
    return out;
  }
  const double estimate = estimated_triangle_count(shape, max_edge);
  if (!(estimate <= static_cast<double>(kMaxShapeTriangles))) {
    char value[32];
    std::snprintf(value, sizeof value, "%g", max_edge);
    const std::string cap = format_count(static_cast<double>(kMaxShapeTriangles));
    out.error = std::isfinite(estimate)
                    ? std::string("max_edge: ") + value + " m would give about " +
                          format_count(two_digits(estimate)) + " triangles, more than the cap of " +
                          cap
                    : std::string("max_edge: ") + value +
                          " m would give far more triangles than the cap of " + cap;
    return out;
  }
  const ShapeRegion region = shape_region(shape, max_edge);
  if (!region.error.empty()) {
    out.error = region.error;
    return out;
  }
  // Refinement budget: each step inserts at most one point, and a mesh of T triangles has
  // about T/2 points; ten times the estimate plus the boundary's points leaves room for
  // the local refinement small input features need, and the cap bounds the time.
  long boundary_points = 0;
  for (const RegionLoop& l : region.loops) boundary_points += static_cast<long>(l.points.size());
  const long budget = std::min<long>(
      kMaxShapeTriangles, 10 * (static_cast<long>(estimate) + boundary_points) + 100'000);
  Triangulation t = triangulate_region(region.loops, max_edge, budget);
  if (!t.error.empty()) {
    out.error = std::string(geometry_key(shape)) + ": " + t.error;
    return out;
  }
  out.mesh.rest = std::move(t.nodes);
  out.mesh.triangles = std::move(t.triangles);
  compute_rest_data(out.mesh);
  return out;
}

}  // namespace

double estimated_triangle_count(const ShapeDef& shape, double max_edge) {
  const double area = shape_area(shape);
  return kTriangleEstimateFactor * area / (std::sqrt(3.0) / 4 * max_edge * max_edge);
}

ShapeMeshResult mesh_shape(const ShapeDef& shape, double max_edge) {
  try {
    {
      std::lock_guard lock(cache_mutex);
      for (const CacheEntry& e : cache)
        if (e.max_edge == max_edge && e.shape == shape) return e.result;
    }
    ShapeMeshResult result = mesh_uncached(shape, max_edge);
    std::lock_guard lock(cache_mutex);
    cache.push_front({shape, max_edge, result});
    if (cache.size() > kCacheSize) cache.pop_back();
    return result;
  } catch (const std::exception& e) {  // out of memory in validation or the cache's copies
    return {Mesh{}, std::string(geometry_key(shape)) + ": meshing failed: " + e.what()};
  }
}

}  // namespace invfree
