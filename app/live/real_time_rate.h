// The playback rate against real time: simulated seconds per wall-clock second over the
// last two seconds of playing (at h = 0.01 and one step per frame a fine mesh shows its
// motion at a fifth of its speed, and the class must be told). Paused frames and a restart
// (the simulated time going back) start the measurement again.
#pragma once

#include <chrono>
#include <cstdio>
#include <deque>
#include <optional>
#include <string>
#include <utility>

namespace invfree::live {

class RealTimeRate {
 public:
  // Once per displayed frame. `wall_s`: seconds on a steady clock (now() by default).
  void count(double sim_time, bool playing, std::optional<double> wall_s = std::nullopt) {
    const double wall = wall_s ? *wall_s : now();
    if (!playing || (!samples_.empty() && sim_time < samples_.back().second)) samples_.clear();
    if (!playing) return;
    samples_.emplace_back(wall, sim_time);
    while (samples_.size() > 2 && wall - samples_[1].first >= kWindowSeconds) samples_.pop_front();
  }
  // Simulated over real seconds, once half a second of playing has been seen.
  std::optional<double> rate() const {
    if (samples_.size() < 2) return std::nullopt;
    const double dt = samples_.back().first - samples_.front().first;
    if (dt < 0.5) return std::nullopt;
    return (samples_.back().second - samples_.front().second) / dt;
  }
  // "0.20× real time", "1.0× real time", "12× real time".
  static std::string text(double rate) {
    char s[48];
    std::snprintf(s, sizeof s, rate >= 10.0 ? "%.0f\u00d7 real time" : "%.2g\u00d7 real time",
                  rate);
    return s;
  }

 private:
  static constexpr double kWindowSeconds = 2.0;
  static double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
  std::deque<std::pair<double, double>> samples_;  // (wall, simulated) seconds
};

}  // namespace invfree::live
