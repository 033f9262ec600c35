#include "collision/orientation.h"

#include <array>
#include <cmath>

namespace invfree {

namespace {

// a + b = sum + error exactly (Knuth's TwoSum, no ordering assumption).
void two_sum(double a, double b, double& sum, double& error) {
  sum = a + b;
  const double b_virtual = sum - a;
  const double a_virtual = sum - b_virtual;
  error = (a - a_virtual) + (b - b_virtual);
}

int sign(double v) {
  return (v > 0.0) - (v < 0.0);
}

}  // namespace

int orientation_exact(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double factors[6][2] = {{a.x(), b.y()},  {-a.x(), c.y()}, {b.x(), c.y()},
                                {-b.x(), a.y()}, {c.x(), a.y()},  {-c.x(), b.y()}};
  // Expansion components in increasing magnitude, non-overlapping (Grow-Expansion keeps
  // both properties); zeros may sit anywhere and do not matter.
  std::array<double, 12> expansion{};
  int length = 0;
  const auto grow = [&](double term) {
    double q = term;
    for (int k = 0; k < length; ++k) two_sum(q, expansion[k], q, expansion[k]);
    expansion[length++] = q;
  };
  for (const auto& f : factors) {
    const double product = f[0] * f[1];
    grow(std::fma(f[0], f[1], -product));  // the product's rounding error, exact
    grow(product);
  }
  for (int k = length - 1; k >= 0; --k)
    if (expansion[k] != 0.0) return sign(expansion[k]);
  return 0;
}

int orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  // Shewchuk's orient2d filter: |error| <= (3 + 16 eps) eps (|left| + |right|).
  constexpr double eps = 0x1p-53;
  constexpr double bound = (3.0 + 16.0 * eps) * eps;
  const double left = (a.x() - c.x()) * (b.y() - c.y());
  const double right = (a.y() - c.y()) * (b.x() - c.x());
  const double det = left - right;
  if (std::abs(det) > bound * (std::abs(left) + std::abs(right))) return sign(det);
  return orientation_exact(a, b, c);
}

}  // namespace invfree
