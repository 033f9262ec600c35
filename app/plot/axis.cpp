#include "app/plot/axis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace invfree {

double AxisRange::to_axis(double v) const {
  if (!std::isfinite(v)) return std::numeric_limits<double>::quiet_NaN();
  if (!log) return v;
  return v > 0.0 ? std::log10(v) : std::numeric_limits<double>::quiet_NaN();
}

AxisRange axis_range(const std::vector<double>& values, bool log) {
  AxisRange r;
  r.log = log;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values) {
    const double a = r.to_axis(v);
    if (!std::isfinite(a)) continue;
    lo = std::min(lo, a);
    hi = std::max(hi, a);
  }
  if (!(hi >= lo)) {  // no data
    r.lo = 0.0;
    r.hi = 1.0;
    return r;
  }
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(lo))) {
    const double pad = log ? 0.5 : std::max(std::abs(lo) * 0.1, 0.5);
    lo -= pad;
    hi += pad;
  }
  // A small margin so that markers on the extremes are not cut by the frame.
  const double margin = 0.05 * (hi - lo);
  r.lo = lo - margin;
  r.hi = hi + margin;
  return r;
}

std::string format_tick(double value) {
  if (value == 0.0) return "0";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", value);
  std::string s = buf;
  // A leading '-' reads better as a real minus sign.
  if (!s.empty() && s[0] == '-') s = "\u2212" + s.substr(1);
  return s;
}

namespace {

// 1-2-5 steps, about six over the range, each labelled.
std::vector<Tick> linear_ticks(const AxisRange& r) {
  std::vector<Tick> ticks;
  const double span = r.hi - r.lo;
  const double raw = span / 6.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  const long i0 = static_cast<long>(std::ceil(r.lo / step - 1e-9)),
             i1 = static_cast<long>(std::floor(r.hi / step + 1e-9));
  for (long i = i0; i <= i1; ++i) {
    Tick t;
    t.value = i * step;
    if (std::abs(t.value) < step * 1e-9) t.value = 0.0;
    t.label = format_tick(t.value);
    ticks.push_back(t);
  }
  return ticks;
}

// Decades (major; labelled, every 2nd/3rd/... when there are many) with minor ticks at
// 2..9; with fewer than two labels, every minor tick labelled, and failing that linear
// 1-2-5 steps.
std::vector<Tick> log_ticks(const AxisRange& r) {
  std::vector<Tick> ticks;
  const double eps = 1e-9 * (r.hi - r.lo);
  const int k0 = static_cast<int>(std::floor(r.lo)), k1 = static_cast<int>(std::ceil(r.hi));
  const int decades_shown = static_cast<int>(std::floor(r.hi + eps) - std::ceil(r.lo - eps)) + 1;
  // With many decades, label every 2nd/3rd/... so that labels do not collide.
  const int label_every = std::max(1, (decades_shown + 7) / 8);
  // With fewer than two decade ticks, label 2 and 5 too (in plain numbers).
  const bool label_minor = decades_shown < 2;
  const bool minor_ticks = decades_shown <= 12;
  for (int k = k0; k <= k1; ++k) {
    for (int m = 1; m <= 9; ++m) {
      if (m > 1 && !minor_ticks) break;
      const double a = k + std::log10(static_cast<double>(m));
      if (a < r.lo - eps || a > r.hi + eps) continue;
      Tick t;
      t.value = m * std::pow(10.0, k);
      t.major = m == 1;
      t.exponent = k;
      if (m == 1) {
        t.labelled = (k % label_every) == 0;
        t.decade_label = !label_minor;
        if (label_minor) t.label = format_tick(t.value);
      } else {
        t.labelled = label_minor && (m == 2 || m == 5);
        t.label = format_tick(t.value);
      }
      ticks.push_back(t);
    }
  }
  // A range inside one decade may hold no 1, 2 or 5: label every minor tick then, and
  // if even that gives fewer than two labels, use linear 1-2-5 steps on the log axis.
  auto labelled = [&] {
    return std::count_if(ticks.begin(), ticks.end(), [](const Tick& t) { return t.labelled; });
  };
  if (labelled() < 2 && minor_ticks)
    for (Tick& t : ticks) {
      t.labelled = true;
      if (t.decade_label) {
        t.decade_label = false;
        t.label = format_tick(t.value);
      } else if (t.label.empty()) {
        t.label = format_tick(t.value);
      }
    }
  if (labelled() < 2) {
    AxisRange linear{false, std::pow(10.0, r.lo), std::pow(10.0, r.hi)};
    std::vector<Tick> fine = linear_ticks(linear);
    for (Tick& t : fine) t.major = false;
    fine.erase(
        std::remove_if(fine.begin(), fine.end(), [](const Tick& t) { return !(t.value > 0.0); }),
        fine.end());
    for (const Tick& t : ticks)
      if (t.major) {
        Tick d = t;
        d.labelled = false;
        fine.push_back(d);
      }
    return fine;
  }
  return ticks;
}

}  // namespace

std::vector<Tick> axis_ticks(const AxisRange& r) {
  return r.log ? log_ticks(r) : linear_ticks(r);
}

std::vector<Tick> value_ticks(std::vector<double> values, const AxisRange& r) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  std::vector<Tick> ticks;
  for (double v : values) {
    const double a = r.to_axis(v);
    if (!std::isfinite(a) || a < r.lo || a > r.hi) continue;
    Tick t;
    t.value = v;
    t.label = format_tick(v);
    ticks.push_back(t);
  }
  return ticks;
}

bool PlotFrame::plottable(double vx, double vy) const {
  return std::isfinite(x.to_axis(vx)) && std::isfinite(y.to_axis(vy));
}

}  // namespace invfree
