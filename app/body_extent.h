// How big a body is at rest, for everything in the app that frames or scales by a body's
// size (cameras, the live window's sliders, the study's error and blow-up scales): its rest
// bounding box in the scene's frame and its width and height. A square keeps the exact
// arithmetic every picture before shapes used (offset +- side / 2, width = height = side),
// so its frames stay bit-identical; any other shape (issue 27) is shape_bounds moved to the
// body's offset.
#pragma once

#include <algorithm>

#include "scene/scene.h"
#include "scene/scene_mesh.h"
#include "shape/shape_region.h"

namespace invfree {

struct BodyExtent {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // rest bounding box, scene frame (m)
  double width = 0, height = 0;           // a square's: exactly its side
  double size() const { return std::max(width, height); }
};

inline BodyExtent body_rest_extent(const PlacedBody& b) {
  BodyExtent e;
  const Eigen::AlignedBox2d box =
      b.shape.kind == ShapeKind::Square ? Eigen::AlignedBox2d() : shape_bounds(b.shape);
  if (box.isEmpty()) {  // the square (or a shape with no points: framed as the square)
    e.x0 = b.offset.x() - 0.5 * b.side;
    e.x1 = b.offset.x() + 0.5 * b.side;
    e.y0 = b.offset.y() - 0.5 * b.side;
    e.y1 = b.offset.y() + 0.5 * b.side;
    e.width = e.height = b.side;
    return e;
  }
  e.x0 = b.offset.x() + box.min().x();
  e.x1 = b.offset.x() + box.max().x();
  e.y0 = b.offset.y() + box.min().y();
  e.y1 = b.offset.y() + box.max().y();
  e.width = box.max().x() - box.min().x();
  e.height = box.max().y() - box.min().y();
  return e;
}

inline BodyExtent body_rest_extent(const SceneDef& s, int body) {
  return body_rest_extent(placed_body(s, body));
}

// The scene's length scale: its side when every body is a square (what every scale before
// shapes read, kept so square scenes' numbers do not move), otherwise the longest side of
// any body's rest bounding box (a 2 m plate is 2 m, whatever [mesh] side says).
inline double scene_length_scale(const SceneDef& s) {
  if (scene_has_only_squares(s)) return s.side;
  double size = 0.0;
  for (int k = 0; k < body_count(s); ++k) size = std::max(size, body_rest_extent(s, k).size());
  return size > 0.0 ? size : s.side;
}

}  // namespace invfree
