#include "solver/line_search_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace invfree {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}
}  // namespace

double smallest_positive_root(double a, double b, double c) {
  if (a == 0.0) {
    if (b == 0.0) return kInf;
    const double t = -c / b;
    return t > 0.0 ? t : kInf;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return kInf;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  double best = kInf;
  const double r1 = q / a;
  if (r1 > 0.0) best = r1;
  if (q != 0.0) {
    const double r2 = c / q;
    if (r2 > 0.0) best = std::min(best, r2);
  }
  return best;
}

double inversion_free_step(const Mesh& mesh, const VecX& x, const VecX& p) {
  double alpha = 1.0;
  for (const auto& tri : mesh.triangles) {
    const Vec2 x1 = x.segment<2>(2 * tri[0]);
    const Vec2 x21 = x.segment<2>(2 * tri[1]) - x1, x31 = x.segment<2>(2 * tri[2]) - x1;
    const Vec2 p1 = p.segment<2>(2 * tri[0]);
    const Vec2 p21 = p.segment<2>(2 * tri[1]) - p1, p31 = p.segment<2>(2 * tri[2]) - p1;
    const double area = cross(x21, x31);
    const double a = cross(p21, p31) / area;
    const double b = (cross(x21, p31) + cross(p21, x31)) / area;
    alpha = std::min(alpha, smallest_positive_root(a, b, 1.0 - kMinAreaFraction));
  }
  return alpha;
}

double signed_area(const VecX& x, const std::array<int, 3>& t) {
  return cross(x.segment<2>(2 * t[1]) - x.segment<2>(2 * t[0]),
               x.segment<2>(2 * t[2]) - x.segment<2>(2 * t[0]));
}

double plane_step(const PlaneFilter& planes, int node_count, const VecX& x, const VecX& p) {
  double alpha = 1.0;
  const int c = 2 * node_count;
  for (int i = 0; i < node_count; ++i) {
    const int y = 2 * i + 1;
    if (planes.ground_on && p[y] < 0.0)
      alpha = std::min(alpha, 0.9 * (x[y] - planes.ground_y) / -p[y]);
    if (planes.ceiling_on) {
      const double closing = p[c] - p[y];  // rate of change of the gap c - y_i
      if (closing < 0.0) alpha = std::min(alpha, 0.9 * (x[c] - x[y]) / -closing);
    }
  }
  return alpha;
}

}  // namespace invfree
