#include "app/render/view_choices.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "app/body_extent.h"
#include "app/colormap.h"
#include "enum_names.h"

namespace invfree::render {

std::optional<ColorRangeMode> parse_color_range_mode(const std::string& name) {
  if (name == "fixed") return ColorRangeMode::Fixed;
  if (name == "run") return ColorRangeMode::Run;
  if (name == "frame") return ColorRangeMode::Frame;
  return std::nullopt;
}

namespace {
constexpr EnumName<ColorRangeMode> kColorRangeModeNames[] = {
    {ColorRangeMode::Fixed, "fixed"},
    {ColorRangeMode::Run, "run"},
    {ColorRangeMode::Frame, "frame"},
};
}  // namespace

const char* color_range_mode_name(ColorRangeMode mode) {
  return enum_name(kColorRangeModeNames, mode);
}

void ColorRangeTracker::apply(double lo, double hi, DrawOptions* options) {
  if (lo > 0.0) run_lo = std::min(run_lo, lo);
  run_hi = std::max(run_hi, hi);
  options->color_range_auto = mode != ColorRangeMode::Fixed;
  switch (mode) {
    case ColorRangeMode::Fixed:
      options->color_range = kDetFRange;
      break;
    case ColorRangeMode::Run:
      options->color_range = auto_det_f_range(run_lo, run_hi);
      break;
    case ColorRangeMode::Frame:
      options->color_range = auto_det_f_range(lo, hi);
      break;
  }
}

void ColorRangeTracker::apply_field(const FrameState& frame, DrawOptions* options) {
  apply_field(std::vector<const FrameState*>{&frame}, options);
}

void ColorRangeTracker::apply_field(const std::vector<const FrameState*>& frames,
                                    DrawOptions* options) {
  options->field_scale.reset();
  if (frames.empty()) return;
  const TriangleField field = frames.front()->color_by;
  if (field == TriangleField::DetF || field == TriangleField::Clamped) return;
  FieldStats now;
  for (const FrameState* f : frames) now = combine_field_stats(now, field_stats(field, f->field));
  if (now.count == 0) return;
  if (mode == ColorRangeMode::Frame) {  // (one frame: the renderer scales it by itself)
    if (frames.size() > 1) options->field_scale = auto_field_scale(field, now);
    return;
  }
  run_field = field_seen ? combine_field_stats(run_field, now) : now;
  field_seen = true;
  options->field_scale = auto_field_scale(field, run_field);
}

namespace {

// The bodies' bounding box (every node).
WorldBox node_box(const VecX& x) {
  WorldBox b{x[0], x[0], x[1], x[1]};
  for (Eigen::Index i = 0; i + 1 < x.size(); i += 2) {
    b.x0 = std::min(b.x0, x[i]);
    b.x1 = std::max(b.x1, x[i]);
    b.y0 = std::min(b.y0, x[i + 1]);
    b.y1 = std::max(b.y1, x[i + 1]);
  }
  return b;
}

WorldBox padded(const WorldBox& b, double pad) {
  return {b.x0 - pad, b.x1 + pad, b.y0 - pad, b.y1 + pad};
}

}  // namespace

Camera FollowCamera::next(const FrameState& state, const PixelRect& plot) {
  return next(state.x, state.scene, plot);
}

Camera FollowCamera::next(const VecX& x, const SceneDef& scene, const PixelRect& plot) {
  if (x.size() < 2) return last.value_or(Camera{});
  const WorldBox body = node_box(x);
  const double size =
      std::max({body.x1 - body.x0, body.y1 - body.y0, 0.2 * scene_length_scale(scene)});
  // Aim: the bodies with a third of their size around them (the planes show when near).
  const Camera target = fit_camera(padded(body, 0.35 * size), plot);
  Camera c = target;
  if (last) {
    constexpr double kRate = 0.08;  // of the way to the target per frame
    c.pixels_per_metre =
        last->pixels_per_metre + kRate * (target.pixels_per_metre - last->pixels_per_metre);
    // Centre (world point at the plot's centre) eased the same way.
    const Vec2 mid(plot.x + 0.5 * plot.w, plot.y + 0.5 * plot.h);
    const Vec2 last_centre = last->to_world(mid), target_centre = target.to_world(mid);
    const Vec2 centre = last_centre + kRate * (target_centre - last_centre);
    // Never so close that a node leaves the picture: the bodies plus a small margin fit.
    const WorldBox must = padded(body, 0.05 * size);
    const double fit = fit_camera(must, plot).pixels_per_metre;
    c.pixels_per_metre = std::min(c.pixels_per_metre, fit);
    const double half_w = 0.5 * plot.w / c.pixels_per_metre,
                 half_h = 0.5 * plot.h / c.pixels_per_metre;
    const double cx = std::clamp(centre.x(), must.x1 - half_w, must.x0 + half_w);
    const double cy = std::clamp(centre.y(), must.y1 - half_h, must.y0 + half_h);
    c.origin = Vec2(mid.x() - c.pixels_per_metre * cx, mid.y() + c.pixels_per_metre * cy);
  }
  last = c;
  return c;
}

std::pair<double, double> bulk_det_f_range(const std::vector<double>& det_f) {
  std::vector<double> d;  // the positive ones: inverted triangles are green on any scale
  for (const double v : det_f)
    if (v > 0.0) d.push_back(v);
  if (d.empty()) return {1.0, 1.0};
  const auto at = [&](double q) {
    const size_t k = std::min(d.size() - 1, static_cast<size_t>(q * (d.size() - 1) + 0.5));
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(k), d.end());
    return d[k];
  };
  const double lo = at(0.10), hi = at(0.90);
  return {lo, hi};
}

std::vector<Vec2> BodyPaths::centroids(const FrameState& state) {
  const int nodes = static_cast<int>(state.x.size() / 2);
  std::vector<Vec2> out;
  for (size_t b = 0; b < state.body_begin.size(); ++b) {
    const int begin = state.body_begin[b];
    const int end = b + 1 < state.body_begin.size() ? state.body_begin[b + 1] : nodes;
    if (end <= begin || begin < 0 || end > nodes) continue;
    Vec2 sum = Vec2::Zero();
    for (int i = begin; i < end; ++i) sum += Vec2(state.x[2 * i], state.x[2 * i + 1]);
    out.push_back(sum / (end - begin));
  }
  return out;
}

void BodyPaths::add(FrameState* state, double dot_radius) {
  const std::vector<Vec2> now = centroids(*state);
  if (paths.size() != now.size()) paths.assign(now.size(), {});
  for (size_t b = 0; b < now.size(); ++b) {
    paths[b].push_back(now[b]);
    const Rgb color = kPathColors[b % std::size(kPathColors)];
    Overlay path;
    path.points = paths[b];
    for (int k = 0; k + 1 < static_cast<int>(path.points.size()); ++k)
      path.segments.push_back({k, k + 1});
    path.color = color;
    path.stroke_width = 2.5;
    state->overlays.push_back(std::move(path));
    Overlay dot;  // where the body is now
    dot.points = {now[b]};
    dot.color = color;
    dot.dot_radius = dot_radius;
    state->overlays.push_back(std::move(dot));
  }
}

bool paths_by_default(const SceneDef& scene) {
  return body_count(scene) > 1;
}

}  // namespace invfree::render
