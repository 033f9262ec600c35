// Least-squares straight line through (log x, log y): the power law y = exp(intercept) *
// x^slope that a log-log chart shows as a line (the study's convergence order, the
// bench's cost against unknowns). Points with x or y not positive and finite are skipped;
// with fewer than two usable points, or all x equal, slope and intercept are NaN.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

namespace invfree {

struct LogLogFit {
  double slope = std::numeric_limits<double>::quiet_NaN();
  double intercept = std::numeric_limits<double>::quiet_NaN();  // of log y at log x = 0
  bool ok() const { return !std::isnan(slope); }
};

LogLogFit fit_loglog(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace invfree
