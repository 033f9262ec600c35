#include "app/study/error.h"

#include <cmath>
#include <limits>

#include "app/plot/loglog_fit.h"

namespace invfree {

double rms_position_error(const std::vector<VecX>& run, const std::vector<VecX>& reference,
                          double side, const std::vector<int>& node_map) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (run.empty() || run.size() != reference.size() || !(side > 0.0)) return nan;
  double sum = 0.0;
  long count = 0;
  for (size_t s = 0; s < run.size(); ++s) {
    const long nodes = run[s].size() / 2;
    if (node_map.empty() ? run[s].size() != reference[s].size()
                         : static_cast<long>(node_map.size()) != nodes)
      return nan;
    for (long i = 0; i < nodes; ++i) {
      const long r = node_map.empty() ? i : node_map[i];
      if (2 * r + 1 >= reference[s].size()) return nan;
      sum += (run[s].segment<2>(2 * i) - reference[s].segment<2>(2 * r)).squaredNorm();
      ++count;
    }
  }
  return std::sqrt(sum / count) / side;
}

std::vector<int> nested_node_map(int n_coarse, int n_fine) {
  if (n_coarse < 1 || n_fine < n_coarse || n_fine % n_coarse != 0) return {};
  const int k = n_fine / n_coarse;
  std::vector<int> map;
  for (int i = 0; i <= n_coarse; ++i)
    for (int j = 0; j <= n_coarse; ++j) map.push_back(i * k * (n_fine + 1) + j * k);
  return map;
}

double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  return fit_loglog(x, y).slope;
}

}  // namespace invfree
