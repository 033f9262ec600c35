#include "app/plot/loglog_fit.h"

#include <algorithm>
#include <cmath>

namespace invfree {

LogLogFit fit_loglog(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    if (!(x[i] > 0.0 && y[i] > 0.0 && std::isfinite(x[i]) && std::isfinite(y[i]))) continue;
    const double a = std::log(x[i]), b = std::log(y[i]);
    sx += a;
    sy += b;
    sxx += a * a;
    sxy += a * b;
    ++n;
  }
  const double denom = n * sxx - sx * sx;
  LogLogFit fit;
  if (n < 2 || !(denom > 0.0)) return fit;
  fit.slope = (n * sxy - sx * sy) / denom;
  fit.intercept = (sy - fit.slope * sx) / n;
  return fit;
}

}  // namespace invfree
