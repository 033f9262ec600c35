// Chart axes: the displayed range of a linear or logarithmic axis from the data, its
// ticks (decades and 2..9 minor ticks on a log axis, 1-2-5 steps on a linear one) and the
// mapping from data to pixels. Inputs: data values (non-finite values, and values <= 0
// on a log axis, are ignored). Outputs: plain structs.
#pragma once

#include <string>
#include <vector>

namespace invfree {

struct AxisRange {
  bool log = false;
  double lo = 0.0, hi = 1.0;       // in axis space: log10 of the value on a log axis
  double to_axis(double v) const;  // data value -> axis space (NaN when not plottable)
};

struct Tick {
  double value = 0.0;  // data units
  bool major = true;
  bool labelled = true;
  bool decade_label = false;  // label drawn as 10^exponent
  int exponent = 0;
  std::string label;  // when not a decade label
};

AxisRange axis_range(const std::vector<double>& values, bool log);
std::vector<Tick> axis_ticks(const AxisRange& range);
// Ticks at exactly these values (sorted, repeats and values the axis cannot show left
// out), each labelled with its value.
std::vector<Tick> value_ticks(std::vector<double> values, const AxisRange& range);
// Plain rendering of a tick value with up to 6 significant digits (%g), a real minus sign.
std::string format_tick(double value);

// The plot rectangle in pixels and the two axes.
struct PlotFrame {
  double left, top, right, bottom;
  AxisRange x, y;
  double to_px_x(double v) const {
    return left + (x.to_axis(v) - x.lo) / (x.hi - x.lo) * (right - left);
  }
  double to_px_y(double v) const {
    return bottom - (y.to_axis(v) - y.lo) / (y.hi - y.lo) * (bottom - top);
  }
  bool plottable(double vx, double vy) const;
};

}  // namespace invfree
