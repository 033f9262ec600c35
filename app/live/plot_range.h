// The y range a live plot draws and labels: the data's smallest and largest values, widened
// about their middle to at least `min_span`, so that a change of 0.001 in min det F is
// drawn (and labelled) as the small change it is, not as a ramp over the whole plot.
#pragma once

#include <algorithm>
#include <vector>

namespace invfree::live {

struct PlotRange {
  float lo = 0.0f, hi = 0.0f;
};

inline PlotRange plot_y_range(const std::vector<float>& values, float min_span) {
  PlotRange r;
  if (!values.empty()) {
    const auto [a, b] = std::minmax_element(values.begin(), values.end());
    r.lo = *a;
    r.hi = *b;
  }
  if (r.hi - r.lo < min_span) {
    const float mid = 0.5f * (r.lo + r.hi);
    r.lo = mid - 0.5f * min_span;
    r.hi = mid + 0.5f * min_span;
  }
  return r;
}

}  // namespace invfree::live
