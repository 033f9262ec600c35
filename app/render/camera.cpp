#include "app/render/camera.h"

#include <algorithm>
#include <cmath>

namespace invfree::render {

FrameLayout frame_layout(int width, int height, PanelMode panel, double text_scale) {
  FrameLayout l;
  l.width = width;
  l.height = height;
  l.scale = std::min(width / 1280.0, height / 720.0) * text_scale;
  const double panel_w =
      panel != PanelMode::Hidden ? std::round(std::min(290.0 * l.scale, 0.45 * width)) : 0.0;
  l.overlay = panel == PanelMode::Overlay;
  l.plot = {0.0, 0.0, l.overlay ? double(width) : width - panel_w, double(height)};
  l.panel = {width - panel_w, 0.0, panel_w, double(height)};
  return l;
}

WorldBox scene_world_box(const SceneDef& scene) {
  const double half = 0.5 * scene.side;
  double y0 = -half, y1 = half;
  if (scene.has_ground) y0 = std::min(y0, scene.ground_y);
  if (scene.has_ceiling) y1 = std::max(y1, scene.ceiling_y);
  // Squashed between the planes down to the ceiling's stop gap, the square spreads
  // sideways; at constant area it is side^2 / gap wide. Capped, for a stop at or
  // below the ground.
  double spread = 1.0;
  if (scene.has_ground && scene.has_ceiling) {
    const double gap = std::max(scene.ceiling_stop - scene.ground_y, 0.25 * scene.side);
    spread = std::clamp(scene.side / gap, 1.0, 4.0);
  }
  const double band = std::max(0.15 * (y1 - y0), 0.1 * scene.side);  // visible plane depth
  const double x_half = half * spread + 0.15 * scene.side;
  double x0 = -x_half, x1 = x_half;
  if (scene.has_ground && scene.ground_normal.x() != 0.0) {
    // A slope (the course's 4_friction): room for the body to slide one side length down
    // it, and the ground's lower end in the picture.
    const Vec2 n = ground_unit_normal(scene);
    (n.x() > 0.0 ? x1 : x0) += (n.x() > 0.0 ? 1.0 : -1.0) * scene.side;
    const double drop = std::abs(n.x() / std::max(n.y(), 0.087)) * std::max(-x0, x1);
    y0 = std::min(y0, scene.ground_y - drop);
  }
  // Hanging from fixed nodes with no ground (the course's 2_dirichlet): room to sag a side.
  if (scene.has_fixed && scene.has_gravity && !scene.has_ground) y0 -= scene.side;
  return {x0, x1, y0 - band, y1 + band};
}

Camera fit_camera(const WorldBox& box, const PixelRect& rect) {
  Camera c;
  c.pixels_per_metre = std::min(rect.w / (box.x1 - box.x0), rect.h / (box.y1 - box.y0));
  const double cx = 0.5 * (box.x0 + box.x1), cy = 0.5 * (box.y0 + box.y1);
  c.origin = Vec2(rect.x + 0.5 * rect.w - c.pixels_per_metre * cx,
                  rect.y + 0.5 * rect.h + c.pixels_per_metre * cy);
  return c;
}

}  // namespace invfree::render
