// The picture choices shared by `invfree render` and `invfree live` that depend on the
// frames shown so far: the det F colour scale's range (fixed 0.25..4, or automatic from
// the run so far or from each frame), the camera that follows the bodies over a movie,
// and when the mesh's edges are too dense to draw.
// Inputs: each frame's state (in order) and its layout. Outputs: DrawOptions fields.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "app/render/camera.h"
#include "app/render/field_legend.h"
#include "app/render/renderer.h"

namespace invfree::render {

// Edges closer than this many pixels only grey the picture (a fine mesh turns into moire)
// and cost the most triangles: they are left out, the outline kept.
constexpr double kMinEdgeSpacingPixels = 6.0;
inline bool edges_legible(const SceneDef& scene, double pixels_per_metre) {
  double edge = body_edge_length(scene, 0);  // the finest body's
  for (int k = 1; k < body_count(scene); ++k) edge = std::min(edge, body_edge_length(scene, k));
  return edge * pixels_per_metre >= kMinEdgeSpacingPixels;
}

// The colour scale's range: Fixed (kDetFRange), Run (auto_det_f_range over every frame so
// far: it only widens), Frame (auto_det_f_range of the frame alone).
enum class ColorRangeMode { Fixed, Run, Frame };
std::optional<ColorRangeMode> parse_color_range_mode(const std::string& name);
const char* color_range_mode_name(ColorRangeMode mode);

// The det F range `invfree render`'s automatic colour scale is chosen from: the 10th and
// 90th percentiles of the frame's positive det F, not its extremes. The corner triangles of
// a squeezed square reach det F 0.39 while its bulk stays at 0.6-0.9; a scale to the
// extremes (0.25..4) paints the bulk the pale tint of the fixed scale, one to the bulk
// colours it clearly and saturates the most compressed tenth, deep blue (the panel's
// markers still give the true min and max).
std::pair<double, double> bulk_det_f_range(const std::vector<double>& det_f);

struct ColorRangeTracker {
  ColorRangeMode mode = ColorRangeMode::Fixed;
  double run_lo = 1.0, run_hi = 1.0;  // det F extremes seen so far (positive ones)
  // Takes the frame's det F extremes; sets options->color_range and color_range_auto.
  void apply(double lo, double hi, DrawOptions* options);
  // The scale of the field the frame is coloured by when it is not det F (Psi, stress):
  // they have no natural fixed range, so Frame gives each frame its own (leaves
  // options->field_scale unset) and Fixed and Run the widest over the frames so far, so
  // that a movie's colours keep their meaning from frame to frame. Unset too for det F,
  // clamped (fixed categories) and a frame without values.
  void apply_field(const FrameState& frame, DrawOptions* options);
  // The same for frames shown together (`render --compare`'s two views, all coloured by
  // the same field): one scale for all, chosen as above from the values of all of them
  // (Frame too sets it then), so that a colour means the same value in every view.
  void apply_field(const std::vector<const FrameState*>& frames, DrawOptions* options);
  void reset() {
    run_lo = run_hi = 1.0;
    field_seen = false;
  }

  bool field_seen = false;  // the field extremes below hold a frame's
  FieldStats run_field{};   // the field's extremes over the frames so far
};

// Where each body has been: its centroid (the mean of its nodes) at every frame so far,
// drawn as a path with a dot at the current centroid (two overlays per body). In a scene
// of several bodies it shows what they did to each other: in `stack-friction` the top
// square drags the bottom one along as it slides off (the bottom's path runs 0.5 m to the
// left), in the frictionless `stack` it leaves it where it was (a dot) -- the two end
// frames look alike without it (the course's chapter 8). On by default where a scene has
// several bodies (`invfree render --paths`).
struct BodyPaths {
  std::vector<std::vector<Vec2>> paths;  // per body, one point per frame added
  // Records the frame's centroids and appends the paths' overlays to state->overlays.
  void add(FrameState* state, double dot_radius);
  void reset() { paths.clear(); }
  // Each body's centroid (the mean of its nodes' positions).
  static std::vector<Vec2> centroids(const FrameState& state);
};
bool paths_by_default(const SceneDef& scene);

// A camera that keeps the bodies framed over a movie: each frame it moves a fraction of
// the way toward the bodies' padded bounding box (so it never jumps), and never less than
// what keeps every node inside the plot area (so no body leaves the picture).
struct FollowCamera {
  std::optional<Camera> last;
  Camera next(const FrameState& state, const PixelRect& plot);
  // The same from the nodes' positions x (2N) of a scene (the live window's state).
  Camera next(const VecX& x, const SceneDef& scene, const PixelRect& plot);
};

}  // namespace invfree::render
