// The det(F) colour scale shared by every picture invfree draws (live window, offscreen
// frames, contact sheets, colour bars): a diverging blue-white-red map, white at
// det F = 1, symmetric in log det F (compression blue, stretch red), saturating at
// det F = 1/kDetFRange and kDetFRange; det F <= 0 (possible only with the invertible
// models) is a flat, unmistakable green that appears nowhere else on the scale.
#pragma once

#include <algorithm>
#include <cmath>

namespace invfree {

struct Rgb {
  float r, g, b;
};

constexpr double kDetFRange = 4.0;
constexpr Rgb kInvertedColor{0.0f, 0.85f, 0.15f};

// Position on the scale in [-1, 1] (-1: det F <= 1/range, 0: det F = 1, 1: >= range).
inline double det_f_scale_position(double det_f, double range = kDetFRange) {
  return std::clamp(std::log(det_f) / std::log(range), -1.0, 1.0);
}

// Colour of a position in [-1, 1] on the diverging scale (ColorBrewer RdBu, reversed).
inline Rgb diverging_color(double t) {
  static constexpr Rgb stops[] = {{0.129f, 0.400f, 0.675f}, {0.404f, 0.663f, 0.812f},
                                  {0.820f, 0.898f, 0.941f}, {1.000f, 1.000f, 1.000f},
                                  {0.992f, 0.859f, 0.780f}, {0.937f, 0.541f, 0.384f},
                                  {0.698f, 0.094f, 0.169f}};
  const double u = (std::clamp(t, -1.0, 1.0) + 1.0) * 3.0;  // 0..6
  const int i = std::min(static_cast<int>(u), 5);
  const float f = static_cast<float>(u - i);
  const Rgb a = stops[i], b = stops[i + 1];
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}

inline Rgb det_f_color(double det_f, double range = kDetFRange) {
  if (!(det_f > 0.0)) return kInvertedColor;
  return diverging_color(det_f_scale_position(det_f, range));
}

// An automatic range for the scale: the smallest of 1.01, 1.02, 1.05, 1.1, 1.2, 1.5, 2, 4,
// 8, ... 1024 that holds det F in [lo, hi] (lo <= 0, inverted, is ignored: green anyway),
// so that a small deformation uses the whole scale and the bar's labels are round numbers.
inline double auto_det_f_range(double lo, double hi) {
  double need = std::max(hi, 1.0);
  if (lo > 0.0) need = std::max(need, 1.0 / lo);
  static constexpr double small[] = {1.01, 1.02, 1.05, 1.1, 1.2, 1.5, 2.0};
  for (double r : small)
    if (need <= r * (1.0 + 1e-12)) return r;
  double r = 2.0;
  while (r < need && r < 1024.0) r *= 2.0;
  return r;
}

}  // namespace invfree
