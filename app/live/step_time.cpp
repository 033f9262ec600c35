#include "app/live/step_time.h"

#include <cstdio>
#include <numeric>

namespace invfree::live {

std::string step_time_text(double ms) {
  char b[48];
  if (!(ms >= 0.0))
    std::snprintf(b, sizeof b, "- ms/step");
  else if (ms < 0.9995)  // μ: the Greek letter the panel's font has (as in μ = 35.7 kPa)
    std::snprintf(b, sizeof b, "%.3g μs/step", ms * 1000.0);
  else if (ms < 99.95)
    std::snprintf(b, sizeof b, "%.3g ms/step", ms);
  else  // (%g would write 1234 as 1.23e+03)
    std::snprintf(b, sizeof b, "%.0f ms/step", ms);
  return b;
}

double shown_step_ms(const std::vector<float>& recent_ms, double last_ms) {
  if (recent_ms.empty()) return last_ms;
  return std::accumulate(recent_ms.begin(), recent_ms.end(), 0.0) / double(recent_ms.size());
}

}  // namespace invfree::live
