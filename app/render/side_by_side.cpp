#include "app/render/side_by_side.h"

#include <algorithm>
#include <cstring>

#include "app/render/view_choices.h"

namespace invfree::render {

FrameState nodes_of_all(const std::vector<const FrameState*>& states) {
  FrameState all;
  if (states.empty()) return all;
  all.scene = states.front()->scene;
  all.time = states.front()->time;
  Eigen::Index n = 0;
  for (const FrameState* s : states) n += s->x.size();
  all.x.resize(n);
  n = 0;
  for (const FrameState* s : states) {
    all.x.segment(n, s->x.size()) = s->x;
    n += s->x.size();
  }
  return all;
}

std::pair<double, double> joint_bulk_det_f_range(const std::vector<const FrameState*>& states) {
  double lo = 0.0, hi = 0.0;
  bool any = false;
  for (const FrameState* s : states) {
    if (s->det_f.empty()) continue;  // (particles only: no det F)
    const auto [l, h] = bulk_det_f_range(s->det_f);
    lo = any ? std::min(lo, l) : l;
    hi = any ? std::max(hi, h) : h;
    any = true;
  }
  return any ? std::pair{lo, hi} : std::pair{1.0, 1.0};
}

void join_side_by_side(const std::vector<std::uint8_t>& left,
                       const std::vector<std::uint8_t>& right, int half_width, int height,
                       std::vector<std::uint8_t>* out) {
  const size_t row = static_cast<size_t>(half_width) * 4;
  out->resize(2 * row * static_cast<size_t>(height));
  for (int y = 0; y < height; ++y) {
    std::memcpy(out->data() + 2 * row * y, left.data() + row * y, row);
    std::memcpy(out->data() + 2 * row * y + row, right.data() + row * y, row);
  }
}

}  // namespace invfree::render
