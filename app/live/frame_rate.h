// Frames per second, averaged over half a second at a time: the live window shows it in
// its title, where it costs no room in the picture or the panel.
#pragma once

#include <chrono>
#include <optional>

namespace invfree::live {

class FrameRateMeter {
 public:
  // Counts a frame; once half a second has passed, returns the rate since the last one.
  std::optional<double> count() {
    ++frames_;
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - start_).count();
    if (dt < 0.5) return std::nullopt;
    const double rate = frames_ / dt;
    frames_ = 0;
    start_ = now;
    return rate;
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  long frames_ = 0;
};

}  // namespace invfree::live
