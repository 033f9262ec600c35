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

void ViewTransform::fit(const WorldBox& box, double rx, double ry, double rw, double rh) {
  const double bw = std::max(box.x1 - box.x0, 1e-6), bh = std::max(box.y1 - box.y0, 1e-6);
  pixels_per_metre = std::clamp(std::min(std::max(rw, 16.0) / bw, std::max(rh, 16.0) / bh),
                                kMinPixelsPerMetre, kMaxPixelsPerMetre);
  // The box centre goes to the middle of the rectangle.
  const Vec2 mid(rx + 0.5 * rw, ry + 0.5 * rh);
  center = Vec2(0.5 * (box.x0 + box.x1), 0.5 * (box.y0 + box.y1));
  center -= to_world(mid) - center;
}

}  // namespace invfree::live
