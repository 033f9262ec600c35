#include "app/render/camera.h"

#include <algorithm>
#include <cmath>

#include "app/body_extent.h"

namespace invfree::render {

FrameLayout frame_layout(int width, int height, PanelMode panel, double text_scale) {
  FrameLayout l;
  l.width = width;
  l.height = height;
  // The det F panel is laid out for 720 px of height: it grows with the text scale only
  // while it still fits the frame's height (a larger UI scale then enlarges the ImGui
  // panel alone), so its bar and labels never crowd.
  l.scale = std::min(std::min(width / 1280.0, height / 720.0) * text_scale, height / 720.0);
  // Nor wider than 45% of the frame: on a narrow one (a phone's page) the panel and its text
  // shrink together, so that no line is cut at the frame's edge.
  l.scale = std::min(l.scale, 0.45 * width / 290.0);
  const double panel_w = panel != PanelMode::Hidden ? std::round(290.0 * l.scale) : 0.0;
  l.overlay = panel == PanelMode::Overlay;
  l.plot = {0.0, 0.0, l.overlay ? double(width) : width - panel_w, double(height)};
  l.panel = {width - panel_w, 0.0, panel_w, double(height)};
  return l;
}

namespace {

// A particle body's rest bounding box (its points, moved to its offset): zero-sized for a
// lone particle; framed as the square when it lists no points.
BodyExtent particle_extent(const PlacedBody& b) {
  if (b.shape.points.empty()) {
    PlacedBody square = b;
    square.shape.kind = ShapeKind::Square;
    return body_rest_extent(square);
  }
  BodyExtent e;
  e.x0 = e.y0 = INFINITY;
  e.x1 = e.y1 = -INFINITY;
  for (const Vec2& p : b.shape.points) {
    e.x0 = std::min(e.x0, b.offset.x() + p.x());
    e.x1 = std::max(e.x1, b.offset.x() + p.x());
    e.y0 = std::min(e.y0, b.offset.y() + p.y());
    e.y1 = std::max(e.y1, b.offset.y() + p.y());
  }
  e.width = e.x1 - e.x0;
  e.height = e.y1 - e.y0;
  return e;
}

}  // namespace

WorldBox scene_world_box(const SceneDef& scene) {
  // Every body's rest bounding box (body_extent.h: a square's exactly as before shapes).
  // `side` and `half` are the largest body's size and half width, `tall` its height.
  double bx0 = INFINITY, bx1 = -INFINITY, by0 = INFINITY, by1 = -INFINITY, side = 0.0;
  double sides = 0.0, half = 0.0, tall = 0.0;
  bool shaped = false;     // some body is not a square
  bool particles = false;  // some body is particles (ShapeKind::Points, no triangles)
  for (int k = 0; k < body_count(scene); ++k) {
    const PlacedBody placed = placed_body(scene, k);
    const BodyExtent b =
        placed.shape.kind == ShapeKind::Points ? particle_extent(placed) : body_rest_extent(placed);
    particles = particles || placed.shape.kind == ShapeKind::Points;
    bx0 = std::min(bx0, b.x0);
    bx1 = std::max(bx1, b.x1);
    by0 = std::min(by0, b.y0);
    by1 = std::max(by1, b.y1);
    side = std::max(side, b.size());
    sides += b.width;
    half = std::max(half, 0.5 * b.width);
    tall = std::max(tall, b.height);
    shaped = shaped || placed.shape.kind != ShapeKind::Square;
  }
  double y0 = by0, y1 = by1;
  if (scene.has_ground) y0 = std::min(y0, scene.ground_y);
  if (scene.has_ceiling) y1 = std::max(y1, scene.ceiling_y);
  // Squashed between the planes down to the ceiling's stop gap, a body spreads sideways;
  // at constant area a square is side^2 / gap wide, a w x h box w h / gap. Capped, for a
  // stop at or below the ground.
  double spread = 1.0;
  if (scene.has_ground && scene.has_ceiling) {
    const double gap = std::max(scene.ceiling_stop - scene.ground_y, 0.25 * tall);
    spread = std::clamp(tall / gap, 1.0, 4.0);
  }
  const double band = std::max(0.15 * (y1 - y0), 0.1 * side);  // visible plane depth
  // Several bodies may end side by side on the ground, squashed, on either side of where
  // they start (the stack's top square slides off the lower one): room for all of them.
  // A square spreads evenly to both sides; a shape may spread to one side only (the
  // c-shape's squashed arms flow out of its open side): room for all of it on either.
  const double one_body = (shaped ? 2.0 * half : half) * (spread - 1.0);
  const double margin = (body_count(scene) > 1 ? sides * spread : one_body) + 0.15 * side;
  double x0 = bx0 - margin, x1 = bx1 + margin;
  if (particles) {
    // Particles on springs swing and stretch about where they start (a lone one has no
    // size at all): room of half the largest body's size, at least kParticleReach, on
    // every side.
    const double reach = std::max(0.5 * side, kParticleReach);
    x0 = std::min(x0, bx0 - reach);
    x1 = std::max(x1, bx1 + reach);
    y0 = std::min(y0, by0 - reach);
    y1 = std::max(y1, by1 + reach);
    // Falling freely (nothing holds them, no ground): room to fall twice that below, so
    // the first half second of a free fall from rest (1.25 m) is in the picture.
    if (scene.has_gravity && !scene.has_ground && !scene.has_fixed) y0 -= 2.0 * reach;
  }
  if (scene.has_ground && scene.ground_normal.x() != 0.0) {
    // A slope (the course's 4_friction): room for the body to slide one side length down
    // it, and the ground's lower end in the picture.
    const Vec2 n = ground_unit_normal(scene);
    (n.x() > 0.0 ? x1 : x0) += (n.x() > 0.0 ? 1.0 : -1.0) * side;
    const double drop = std::abs(n.x() / std::max(n.y(), 0.087)) * std::max(-x0, x1);
    y0 = std::min(y0, scene.ground_y - drop);
  }
  // Hanging from fixed nodes with no ground (the course's 2_dirichlet): room to sag a side.
  if (scene.has_fixed && scene.has_gravity && !scene.has_ground) y0 -= side;
  return {x0, x1, y0 - band, y1 + band};
}

Camera fit_camera(const WorldBox& box_in, const PixelRect& rect) {
  // A box of no size (a lone particle) or no finite size gets kParticleReach around its
  // centre (or around the origin), so that the scale stays finite.
  WorldBox box = box_in;
  const auto widen = [](double& lo, double& hi) {
    if (hi - lo > 0.0 && std::isfinite(hi - lo)) return;
    const double mid = std::isfinite(lo + hi) ? 0.5 * (lo + hi) : 0.0;
    lo = mid - kParticleReach;
    hi = mid + kParticleReach;
  };
  widen(box.x0, box.x1);
  widen(box.y0, box.y1);
  Camera c;
  c.pixels_per_metre = std::min(rect.w / (box.x1 - box.x0), rect.h / (box.y1 - box.y0));
  const double cx = 0.5 * (box.x0 + box.x1), cy = 0.5 * (box.y0 + box.y1);
  c.origin = Vec2(rect.x + 0.5 * rect.w - c.pixels_per_metre * cx,
                  rect.y + 0.5 * rect.h + c.pixels_per_metre * cy);
  return c;
}

}  // namespace invfree::render
