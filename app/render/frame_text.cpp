#include "app/render/frame_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/colormap.h"

namespace invfree::render {

std::string format_si(double value, const char* unit) {
  static constexpr struct {
    double factor;
    const char* prefix;
  } kPrefixes[] = {{1e9, "G"}, {1e6, "M"}, {1e3, "k"}, {1.0, ""}, {1e-3, "m"}};
  char buf[64];
  if (!std::isfinite(value)) {
    std::snprintf(buf, sizeof buf, "%g %s", value, unit);
    return buf;
  }
  const double a = std::fabs(value);
  if (a == 0.0) return std::string("0 ") + unit;
  for (const auto& p : kPrefixes) {
    // Round to three significant digits first, so that 999.6 becomes "1.00 k", not "1000".
    if (a >= p.factor * 0.9995 || p.factor == 1e-3) {
      const double v = value / p.factor;
      const double av = std::fabs(v);
      const int decimals = av >= 99.95 ? 0 : av >= 9.995 ? 1 : 2;
      std::snprintf(buf, sizeof buf, "%.*f %s%s", decimals, v, p.prefix, unit);
      return buf;
    }
  }
  return "";
}

std::string format_time(double t, double h) {
  int decimals = 2;
  if (h > 0.0) decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(h) - 1e-9)), 2, 6);
  char buf[64];
  std::snprintf(buf, sizeof buf, "t = %.*f s", decimals, t);
  return buf;
}

const char* model_display_name(Model m) {
  return model_label(m);  // the model's own label (material/models.h)
}

std::vector<std::string> method_lines(const SceneDef& scene) {
  switch (scene.integrator) {
    case Integrator::SymplecticEuler:
      return {"symplectic Euler", "explicit: no Newton, no filter"};
    case Integrator::Static:
    case Integrator::ImplicitEuler: {
      const char* projection = scene.projection == HessianProjection::Diagonal
                                   ? "diagonal projection"
                               : scene.projection == HessianProjection::Full ? "full projection"
                                                                             : "no projection";
      return {scene.is_static() ? "static (load steps)" : "implicit Euler",
              std::string(projection) + (scene.inversion_filter ? ", filter on" : ", filter off")};
    }
  }
  return {};
}

std::vector<ColorBarTick> color_bar_ticks(double range) {
  std::vector<ColorBarTick> ticks;
  if (range < 2.0) {  // an automatic range (auto_det_f_range): its ends and 1
    for (const double v : {1.0 / range, 1.0, range}) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.3g", v);
      ticks.push_back({v, det_f_scale_position(v, range), buf});
    }
    return ticks;
  }
  const int n = static_cast<int>(std::floor(std::log2(range) + 1e-9));
  // At most nine ticks (a run that reaches det F 0.001 has a range of 1024: 21 powers of
  // two, whose labels overlapped).
  const int stride = (2 * n + 1 + 8) / 9;
  for (int k = -n; k <= n; ++k) {
    if (k % stride != 0) continue;
    ColorBarTick t;
    t.value = std::ldexp(1.0, k);
    t.position = det_f_scale_position(t.value, range);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", t.value);
    t.label = buf;
    ticks.push_back(t);
  }
  return ticks;
}

}  // namespace invfree::render
