#include "app/live/view_transform.h"

#include <algorithm>
#include <cmath>

namespace invfree::live {

namespace {
constexpr double kMinPixelsPerMetre = 5.0, kMaxPixelsPerMetre = 1e5;
}

void ViewTransform::zoom_at(const Vec2& s, double factor) {
  if (!(factor > 0.0) || !std::isfinite(factor)) return;
  const Vec2 anchor = to_world(s);
  pixels_per_metre = std::clamp(pixels_per_metre * factor, kMinPixelsPerMetre, kMaxPixelsPerMetre);
  // Keep `anchor` under `s`.
  center += anchor - to_world(s);
}

void ViewTransform::fit(const WorldBox& box, double left_inset, double margin) {
  const double avail_w = std::max(width - left_inset - 2.0 * margin, 16.0);
  const double avail_h = std::max(height - 2.0 * margin, 16.0);
  const double bw = std::max(box.x1 - box.x0, 1e-6), bh = std::max(box.y1 - box.y0, 1e-6);
  pixels_per_metre = std::clamp(std::min(avail_w / bw, avail_h / bh), kMinPixelsPerMetre, kMaxPixelsPerMetre);
  // The box centre goes to the middle of the free area.
  const double free_mid_x = left_inset + 0.5 * (width - left_inset);
  center = Vec2(0.5 * (box.x0 + box.x1) - (free_mid_x - 0.5 * width) / pixels_per_metre,
                0.5 * (box.y0 + box.y1));
}

}  // namespace invfree::live
