#include "app/render/field_legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace invfree::render {

FieldStats field_stats(TriangleField field, const std::vector<double>& values) {
  FieldStats s;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    if (s.count == 0) s.min = s.max = v;
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
    if (v > 0.0 && (s.min_positive == 0.0 || v < s.min_positive)) s.min_positive = v;
    s.max_abs = std::max(s.max_abs, std::abs(v));
    ++s.count;
    if (field == TriangleField::Clamped)
      ++s.category_counts[std::clamp(static_cast<int>(std::lround(v)), 0, kClampedCategories - 1)];
  }
  return s;
}

FieldStats combine_field_stats(const FieldStats& a, const FieldStats& b) {
  if (a.count == 0) return b;
  if (b.count == 0) return a;
  FieldStats s = a;
  s.min = std::min(a.min, b.min);
  s.max = std::max(a.max, b.max);
  if (b.min_positive > 0.0 && (s.min_positive == 0.0 || b.min_positive < s.min_positive))
    s.min_positive = b.min_positive;
  s.max_abs = std::max(a.max_abs, b.max_abs);
  s.count = a.count + b.count;
  for (int k = 0; k < kClampedCategories; ++k) s.category_counts[k] += b.category_counts[k];
  return s;
}

FieldScale auto_field_scale(TriangleField field, const FieldStats& stats) {
  switch (field) {
    case TriangleField::DetF: {
      const double r = auto_det_f_range(stats.min, stats.count > 0 ? stats.max : 1.0);
      return {TriangleField::DetF, 1.0 / r, r, true};
    }
    case TriangleField::Psi:
      return auto_psi_scale(stats.min_positive, stats.max);
    case TriangleField::Stress:
      return auto_stress_scale(stats.max_abs);
    case TriangleField::Clamped:
      return clamped_scale();
  }
  return {};
}

std::string format_round_si(double value, const char* unit) {
  if (value == 0.0) return "0";
  char buf[64];
  if (!std::isfinite(value)) {
    std::snprintf(buf, sizeof buf, "%g %s", value, unit);
    return buf;
  }
  // Three significant digits first, so that 999.7 is "1 k", not "1000".
  const double a = std::abs(value);
  const double digits = std::pow(10.0, std::floor(std::log10(a)) - 2.0);
  const double rounded = std::round(a / digits) * digits;
  static constexpr struct {
    double factor;
    const char* prefix;
  } kPrefixes[] = {{1e9, "G"}, {1e6, "M"}, {1e3, "k"}, {1.0, ""}, {1e-3, "m"}};
  for (const auto& p : kPrefixes) {
    if (rounded >= p.factor * (1.0 - 1e-9) || p.factor == 1e-3) {
      std::snprintf(buf, sizeof buf, "%s%.3g %s%s", value < 0.0 ? "−" : "", rounded / p.factor,
                    p.prefix, unit);
      return buf;
    }
  }
  return "";
}

FieldUnit field_unit(const FieldScale& scale) {
  if (scale.field != TriangleField::Stress) return {};
  static constexpr struct {
    double factor;
    const char* name;
  } kUnits[] = {{1e9, "GPa"}, {1e6, "MPa"}, {1e3, "kPa"}, {1.0, "Pa"}};
  const double top = std::max(std::abs(scale.lo), std::abs(scale.hi));
  for (const auto& u : kUnits)
    if (top >= u.factor * (1.0 - 1e-9)) return {u.factor, u.name};
  return {};
}

std::string format_in_unit(double value, const FieldUnit& unit) {
  if (value == 0.0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s%.3g", value < 0.0 ? "−" : "", std::abs(value) / unit.factor);
  return buf;
}

std::vector<FieldTick> field_bar_ticks(const FieldScale& s) {
  std::vector<FieldTick> ticks;
  const FieldUnit unit = field_unit(s);
  const auto add = [&](double v, std::string label = "") {
    if (label.empty()) label = format_in_unit(v, unit);
    ticks.push_back({v, field_bar_position(s, v), label});
  };
  switch (s.field) {
    case TriangleField::DetF:
      break;  // frame_text.h's color_bar_ticks
    case TriangleField::Psi: {
      // Between the ends: the decades, and under two decades 2 and 5 times them too, but
      // none closer to another tick than this (a fraction of the bar): its label would
      // crowd.
      constexpr double kMinGap = 0.12;
      // Decades apart, each label with its own prefix ("≤ 0.2 Pa", "10 Pa", "2 kPa").
      add(s.lo, "≤ " + format_round_si(s.lo, "Pa"));  // less energy takes the bottom colour
      const bool fine = s.hi / s.lo < 100.0 * (1.0 - 1e-9);
      double last = 0.0;
      for (double d = std::pow(10.0, std::floor(std::log10(s.lo))); d < s.hi * (1 - 1e-9);
           d *= 10.0) {
        for (const double m : {1.0, 2.0, 5.0}) {
          if (m != 1.0 && !fine) continue;
          const double v = m * d;
          if (v <= s.lo * (1 + 1e-9) || v >= s.hi * (1 - 1e-9)) continue;
          const double t = field_bar_position(s, v);
          if (t - last >= kMinGap && t <= 1.0 - kMinGap) {
            add(v, format_round_si(v, "Pa"));
            last = t;
          }
        }
      }
      add(s.hi, format_round_si(s.hi, "Pa"));
      break;
    }
    case TriangleField::Stress:
      for (const double f : {-1.0, -0.5, 0.0, 0.5, 1.0}) add(f * s.hi);
      break;
    case TriangleField::Clamped:
      for (int k = 0; k < kClampedCategories; ++k) add(k, std::to_string(k));
      break;
  }
  return ticks;
}

FieldLegendWords field_legend_words(const FieldScale& scale) {
  const std::string automatic = scale.automatic ? " (auto scale)" : "";
  const std::string unit = field_unit(scale).name;
  switch (scale.field) {
    case TriangleField::DetF:
      return {"det F" + automatic, "= area now / area at rest", "stretch", "compression"};
    case TriangleField::Psi:
      // Pa = J/m^3: the energy density's own unit, said both ways.
      return {"Ψ" + automatic, "energy density, Pa = J/m³\nlog scale", "", ""};
    case TriangleField::Stress:
      return {"stress" + automatic, "largest |principal Cauchy stress|, signed, in " + unit,
              "tension", "compression"};
    case TriangleField::Clamped:
      return {"clamped", "eigenvalues of dP/dF the PSD projection sets to 0", "", ""};
  }
  return {};
}

}  // namespace invfree::render
