// The live window's 2D camera: world (metres, y up) <-> window pixels (y down), with
// pan, zoom about a point, and fit-to-box. The visible world rectangle is what the
// shared renderer is asked to draw, so picking a node under the cursor uses the same map.
#pragma once

#include "types.h"

namespace invfree::live {

struct WorldBox {
  double x0, y0, x1, y1;  // x0 < x1, y0 < y1
};

struct ViewTransform {
  Vec2 center = Vec2::Zero();  // world point at the middle of the viewport
  double pixels_per_metre = 300.0;
  double width = 1280.0, height = 720.0;  // viewport, pixels

  Vec2 to_screen(const Vec2& w) const {
    return {0.5 * width + (w.x() - center.x()) * pixels_per_metre,
            0.5 * height - (w.y() - center.y()) * pixels_per_metre};
  }
  Vec2 to_world(const Vec2& s) const {
    return {center.x() + (s.x() - 0.5 * width) / pixels_per_metre,
            center.y() - (s.y() - 0.5 * height) / pixels_per_metre};
  }
  // The world rectangle the viewport shows.
  WorldBox visible() const {
    const Vec2 a = to_world({0.0, height}), b = to_world({width, 0.0});
    return {a.x(), a.y(), b.x(), b.y()};
  }
  // Moves the picture by (dx, dy) pixels.
  void pan(double dx, double dy) {
    center.x() -= dx / pixels_per_metre;
    center.y() += dy / pixels_per_metre;
  }
  // Zooms by `factor` keeping the world point under screen point `s` fixed.
  void zoom_at(const Vec2& s, double factor);
  // Shows `box` whole (the largest scale), centred in the pixel rectangle (rx, ry, rw, rh)
  // of the viewport (top-left corner and size).
  void fit(const WorldBox& box, double rx, double ry, double rw, double rh);
};

}  // namespace invfree::live
