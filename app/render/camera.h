// Where things go in a frame. Inputs: the frame size in pixels and the scene definition.
// Outputs: the frame layout (the plot area holding the world on the left, the panel with
// the text and the colour bar on the right, and a size scale for fonts and lines) and the
// camera mapping world metres (y up) to pixels (origin top-left, y down).
//
// The camera is fixed per scene: it is derived from the scene definition only (each
// body's rest bounding box, app/body_extent.h; ground, ceiling start and stop), never from
// the moving state, so a movie never jumps. The box it frames holds every body at rest,
// the ground, the ceiling's start, a band of each plane, and the widest a body can get when
// squashed to the ceiling's stop gap at constant area (det F <= 1 under compression; a
// shape that is not a square may spread to one side only, so it gets that width on either
// side). Particles (a body of ShapeKind::Points: the course's chapter 0) get room of half
// their size, at least kParticleReach, on every side, and twice that below when they fall
// freely (gravity, nothing fixed, no ground). With no plane (plate-hole) the bodies get a margin of
// at least a tenth of the largest one's size on every side. A body that leaves that box (a free
// fall with no ground) leaves the picture.
#pragma once

#include <algorithm>
#include <cmath>

#include "scene/scene.h"
#include "types.h"

namespace invfree::render {

struct PixelRect {
  double x = 0, y = 0, w = 0, h = 0;  // top-left corner and size
};

struct FrameLayout {
  int width = 0, height = 0;
  // Sizes are designed at 1280x720: min(width/1280, height/720), times the text scale.
  double scale = 1.0;
  PixelRect plot;        // the world
  PixelRect panel;       // text and colour bar
  bool overlay = false;  // the panel lies over the world's right part (plot: whole frame)
};

// How the side panel shares the frame with the world.
enum class PanelMode { Side, Overlay, Hidden };

// With `panel` Hidden the plot takes the whole frame; Overlay: the plot takes the whole
// frame and the panel is drawn over its right part. `text_scale` enlarges the panel and
// its text (the live window's UI scale; 1 for `invfree render`).
FrameLayout frame_layout(int width, int height, PanelMode panel = PanelMode::Side,
                         double text_scale = 1.0);
inline FrameLayout frame_layout(int width, int height, bool panel) {
  return frame_layout(width, height, panel ? PanelMode::Side : PanelMode::Hidden);
}

// A titled view (DrawOptions::title: `invfree render --compare`'s two views) has a heading
// band across the plot's top, kept clear of the world: its height in pixels, and the plot
// area below it, where the camera frames the bodies.
inline double title_band_height(const FrameLayout& L) {
  return std::max(34.0, std::round(62.0 * L.scale));
}
inline PixelRect below_title(const FrameLayout& L) {
  const double band = title_band_height(L);
  return {L.plot.x, L.plot.y + band, L.plot.w, L.plot.h - band};
}

struct WorldBox {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
};

WorldBox scene_world_box(const SceneDef& scene);

// Around particles, and around a box of no size (fit_camera), at least this much (m).
constexpr double kParticleReach = 0.5;

struct Camera {
  double pixels_per_metre = 1.0;
  Vec2 origin = Vec2::Zero();  // pixel position of the world origin
  Vec2 to_pixel(const Vec2& world) const {
    return {origin.x() + pixels_per_metre * world.x(), origin.y() - pixels_per_metre * world.y()};
  }
  Vec2 to_world(const Vec2& pixel) const {
    return {(pixel.x() - origin.x()) / pixels_per_metre,
            (origin.y() - pixel.y()) / pixels_per_metre};
  }
};

// The largest uniform scale showing all of `box` inside `rect`, centred (a box of no size
// along an axis is widened to 2 kParticleReach there).
Camera fit_camera(const WorldBox& box, const PixelRect& rect);

// The camera of a scene in a frame of this layout.
inline Camera scene_camera(const SceneDef& scene, const FrameLayout& layout) {
  return fit_camera(scene_world_box(scene), layout.plot);
}

}  // namespace invfree::render
