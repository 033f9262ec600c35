// Logarithmic slider mapping: a slider position t in [0, 1] <-> a value in [lo, hi]
// with equal ratios per equal distance (so mu from 1e2 to 1e8 gets as much travel per
// decade at the soft end as at the stiff end). With `zero_at_left`, t = 0 is exactly 0
// (lambda = 0 is a valid material) and (0, 1] covers [lo, hi] logarithmically.
#pragma once

#include <algorithm>
#include <cmath>

namespace invfree::live {

struct LogSlider {
  double lo, hi;  // 0 < lo < hi
  bool zero_at_left = false;

  double value(double t) const {
    t = std::clamp(t, 0.0, 1.0);
    if (zero_at_left && t == 0.0) return 0.0;
    // The ends exactly (exp(log(hi)) can round past hi, which read as out of range).
    if (t == 0.0) return lo;
    if (t == 1.0) return hi;
    return std::clamp(std::exp(std::log(lo) + t * (std::log(hi) - std::log(lo))), lo, hi);
  }
  double position(double v) const {
    if (!(v > lo)) return 0.0;  // also NaN and, with zero_at_left, 0
    if (!(v < hi)) return 1.0;
    return (std::log(v) - std::log(lo)) / (std::log(hi) - std::log(lo));
  }
};

}  // namespace invfree::live
