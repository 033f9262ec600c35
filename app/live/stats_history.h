// A fixed-capacity history of one statistic over the last steps (ms per step, min det F)
// for the panel's small plots. Pushing past the capacity drops the oldest value.
// `values()` returns them oldest first, ready for ImGui::PlotLines.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace invfree::live {

class StatsHistory {
 public:
  explicit StatsHistory(std::size_t capacity = 300) : buf_(capacity) {}

  void push(float v) {
    buf_[head_] = v;
    head_ = (head_ + 1) % buf_.size();
    size_ = std::min(size_ + 1, buf_.size());
  }
  void clear() { head_ = size_ = 0; }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return buf_.size(); }
  bool empty() const { return size_ == 0; }
  float back() const { return buf_[(head_ + buf_.size() - 1) % buf_.size()]; }

  std::vector<float> values() const {
    std::vector<float> out(size_);
    const std::size_t start = (head_ + buf_.size() - size_) % buf_.size();
    for (std::size_t i = 0; i < size_; ++i) out[i] = buf_[(start + i) % buf_.size()];
    return out;
  }
  float min() const {
    const auto v = values();
    return v.empty() ? 0.0f : *std::min_element(v.begin(), v.end());
  }
  float max() const {
    const auto v = values();
    return v.empty() ? 0.0f : *std::max_element(v.begin(), v.end());
  }

 private:
  std::vector<float> buf_;
  std::size_t head_ = 0, size_ = 0;
};

}  // namespace invfree::live
