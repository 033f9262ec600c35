// The colour scales of the lecture's other triangle fields (core/triangle_fields.h), beside
// the det F scale of app/colormap.h; the renderer's fills and legends, the live window and
// contact sheets read them all from here.
//
//  - Psi (energy density, Pa = J/m^3): sequential, light yellow (little energy) to dark red,
//    on a LOG scale. Psi grows like mu * strain^2, so a squashed square's corners hold
//    hundreds of times the energy of its middle; on a linear scale the whole body but a few
//    triangles would be one pale colour. Each decade gets the same length of the bar.
//  - stress (the principal Cauchy stress of largest magnitude, signed, Pa): the diverging
//    det F colours (tension red, compression blue, white at zero) on a linear scale
//    symmetric around 0. Signed, not von Mises: a mechanics teacher wants to see where the
//    body is in compression and where in tension, which an unsigned measure hides.
//  - clamped (how many of dP/dF's four eigenvalues the PSD projection sets to zero): five
//    discrete colours, white for 0 (Newton's Hessian is the true one) to dark red for 4.
// No colour of these scales is the inverted green (kInvertedColor).
#pragma once

#include <algorithm>
#include <cmath>

#include "app/colormap.h"
#include "triangle_fields.h"

namespace invfree {

// Colour of a position in [0, 1] on the sequential scale (ColorBrewer YlOrRd, 9 classes).
inline Rgb sequential_color(double t) {
  static constexpr Rgb stops[] = {
      {1.000f, 1.000f, 0.800f}, {1.000f, 0.929f, 0.627f}, {0.996f, 0.851f, 0.463f},
      {0.996f, 0.698f, 0.298f}, {0.992f, 0.553f, 0.235f}, {0.988f, 0.306f, 0.165f},
      {0.890f, 0.102f, 0.110f}, {0.741f, 0.000f, 0.149f}, {0.502f, 0.000f, 0.149f}};
  constexpr int kIntervals = 8;
  const double u = std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0) * kIntervals;
  const int i = std::min(static_cast<int>(u), kIntervals - 1);
  const float f = static_cast<float>(u - i);
  const Rgb a = stops[i], b = stops[i + 1];
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}
constexpr int kSequentialStops = 9;

// How many of the four eigenvalues can be clamped: 0..4, one colour each (ColorBrewer
// OrRd, with white for 0).
constexpr int kClampedCategories = 5;
inline Rgb clamped_color(int count) {
  static constexpr Rgb colors[kClampedCategories] = {{1.000f, 1.000f, 1.000f},
                                                     {0.992f, 0.831f, 0.620f},
                                                     {0.988f, 0.553f, 0.349f},
                                                     {0.843f, 0.188f, 0.122f},
                                                     {0.498f, 0.000f, 0.000f}};
  return colors[std::clamp(count, 0, kClampedCategories - 1)];
}

// The smallest of 1, 2, 5 x 10^k at or above x > 0, and the largest at or below it.
inline double nice_ceil(double x) {
  if (!(x > 0.0) || !std::isfinite(x)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= x * (1.0 - 1e-12)) return m * decade;
  return 10.0 * decade;
}
inline double nice_floor(double x) {
  if (!(x > 0.0) || !std::isfinite(x)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {10.0, 5.0, 2.0, 1.0})
    if (m * decade <= x * (1.0 + 1e-12)) return m * decade;
  return decade;
}

// A field's colour scale. det F: 1/hi..hi (lo = 1/hi), log, as colormap.h. Psi: lo..hi
// (Pa, both > 0), log; values at or below lo take the bottom colour. Stress: -hi..hi (Pa),
// linear (lo = -hi). Clamped: the categories 0..4 (lo = 0, hi = 4).
struct FieldScale {
  TriangleField field = TriangleField::DetF;
  double lo = 1.0 / kDetFRange, hi = kDetFRange;
  bool automatic = false;  // chosen from the data (the bar says so)
};

// Psi spans this many decades at most: energy 10^4 times below the frame's largest is
// "none" for the story (it takes the bottom colour), and the decades that hold the data
// get the colours.
constexpr double kPsiMaxDecades = 4.0;

// The Psi scale of values whose smallest positive one is `min_positive` and largest `max`:
// from nice_floor(min_positive) to nice_ceil(max) (a step of 1, 2, 5 apart at least), at
// most kPsiMaxDecades. No positive value (a body at rest): 1..10 Pa.
inline FieldScale auto_psi_scale(double min_positive, double max) {
  FieldScale s{TriangleField::Psi, 1.0, 10.0, true};
  if (!(max > 0.0) || !std::isfinite(max)) return s;
  s.hi = nice_ceil(max);
  const double floor_lo = s.hi * std::pow(10.0, -kPsiMaxDecades);
  s.lo = min_positive > 0.0 ? nice_floor(min_positive) : floor_lo;
  if (s.lo >= s.hi * (1.0 - 1e-12)) s.lo = nice_floor(0.99 * s.hi);  // one step below
  s.lo = std::max(s.lo, floor_lo);
  return s;
}

// The stress scale: -S..S with S = nice_ceil(largest |value|); 1 Pa when all are zero.
inline FieldScale auto_stress_scale(double max_abs) {
  const double S = max_abs > 0.0 && std::isfinite(max_abs) ? nice_ceil(max_abs) : 1.0;
  return {TriangleField::Stress, -S, S, true};
}

inline FieldScale clamped_scale() {
  return {TriangleField::Clamped, 0.0, kClampedCategories - 1.0, false};
}

// Where `value` lies on the scale's bar, 0 at its bottom and 1 at its top (clamped).
inline double field_bar_position(const FieldScale& s, double value) {
  double t = 0.0;
  switch (s.field) {
    case TriangleField::DetF:
      t = value > 0.0 ? 0.5 * (det_f_scale_position(value, s.hi) + 1.0) : 0.0;
      break;
    case TriangleField::Psi:
      t = value > s.lo ? std::log(value / s.lo) / std::log(s.hi / s.lo) : 0.0;
      break;
    case TriangleField::Stress:
      t = 0.5 * (value / s.hi + 1.0);
      break;
    case TriangleField::Clamped:
      t = (std::round(value) + 0.5) / kClampedCategories;
      break;
  }
  return std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
}

// The colour of `value` on the scale.
inline Rgb field_color(const FieldScale& s, double value) {
  switch (s.field) {
    case TriangleField::DetF:
      return det_f_color(value, s.hi);
    case TriangleField::Psi:
      return sequential_color(field_bar_position(s, value));
    case TriangleField::Stress:
      return diverging_color(std::isnan(value) ? 0.0 : value / s.hi);
    case TriangleField::Clamped:
      return clamped_color(static_cast<int>(std::lround(std::isnan(value) ? 0.0 : value)));
  }
  return {0.5f, 0.5f, 0.5f};
}

}  // namespace invfree
