// Helpers shared by the tests: reproducible random deformation gradients (including
// near-degenerate ones) and central finite differences.
#pragma once

#include <functional>
#include <random>
#include <vector>

#include "material/polar_svd.h"
#include "types.h"

namespace invfree::test {

// Deformation gradients R(a) diag(s1, s2) R(b) covering: generic stretches, s1 ~ s2
// (to 1e-9 relative), small singular values (down to 1e-3), and -- when `allow_inverted`
// -- negative determinants and a zero singular value's neighbourhood.
inline std::vector<Mat2> sample_deformation_gradients(bool allow_inverted, int count = 200,
                                                      unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-3.14159, 3.14159), stretch(0.3, 2.0), unit(0, 1);
  std::vector<Mat2> out;
  for (int k = 0; k < count; ++k) {
    double s1 = stretch(rng), s2 = stretch(rng);
    switch (k % 5) {
      case 1:
        s2 = s1 * (1.0 + 1e-9 * (unit(rng) - 0.5));
        break;  // nearly equal
      case 2:
        s2 = s1;
        break;  // exactly equal
      case 3:
        s2 = 1e-3 + 1e-2 * unit(rng);
        break;  // small
      default:
        break;
    }
    if (allow_inverted && k % 3 == 0) s2 = -s2;
    out.push_back(rotation(angle(rng)) * Vec2(s1, s2).asDiagonal() * rotation(angle(rng)));
  }
  out.push_back(Mat2::Identity());
  return out;
}

// Central difference of a scalar function of a vector, step scaled per call.
template <class Vec>
Vec fd_gradient(const std::function<double(const Vec&)>& f, const Vec& x, double eps) {
  Vec g = x;
  for (int i = 0; i < x.size(); ++i) {
    Vec a = x, b = x;
    a[i] += eps;
    b[i] -= eps;
    g[i] = (f(a) - f(b)) / (2 * eps);
  }
  return g;
}

// Relative error |a - b| / max(|b|, floor).
template <class A, class B>
double relative_error(const A& a, const B& b, double floor = 1.0) {
  return (a - b).norm() / std::max(b.norm(), floor);
}

}  // namespace invfree::test
