#include "app/render/frame_vertices.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/render/frame_text.h"

namespace invfree::render {

namespace {

// The figure's palette (the det F colours come from app/colormap.h).
constexpr Rgba kPanelBackground{1.0f, 1.0f, 1.0f, 1.0f};
constexpr Rgba kInk{0.12f, 0.12f, 0.12f, 1.0f};
constexpr Rgba kMutedInk{0.38f, 0.38f, 0.38f, 1.0f};
constexpr Rgba kSeparator{0.84f, 0.84f, 0.84f, 1.0f};
constexpr Rgba kPlaneFill{0.90f, 0.90f, 0.90f, 1.0f};
constexpr Rgba kPlaneEdge{0.22f, 0.22f, 0.22f, 1.0f};
constexpr Rgba kMeshEdge{0.08f, 0.08f, 0.08f, 0.38f};
constexpr Rgba kOutline{0.08f, 0.08f, 0.08f, 1.0f};
constexpr Rgba kInvertedInk{0.0f, 0.50f, 0.10f, 1.0f};  // the inverted green, dark enough for text

void add_triangle(Shapes& s, Vec2 a, Vec2 b, Vec2 c, Rgba ca, Rgba cb, Rgba cc) {
  s.push_back({float(a.x()), float(a.y()), ca});
  s.push_back({float(b.x()), float(b.y()), cb});
  s.push_back({float(c.x()), float(c.y()), cc});
}
void add_triangle(Shapes& s, Vec2 a, Vec2 b, Vec2 c, Rgba color) {
  add_triangle(s, a, b, c, color, color, color);
}

// Axis-aligned rectangle; colour `top` at y0 and `bottom` at y1 (a vertical gradient).
void add_rect(Shapes& s, double x0, double y0, double x1, double y1, Rgba top, Rgba bottom) {
  add_triangle(s, {x0, y0}, {x1, y0}, {x1, y1}, top, top, bottom);
  add_triangle(s, {x0, y0}, {x1, y1}, {x0, y1}, top, bottom, bottom);
}
void add_rect(Shapes& s, double x0, double y0, double x1, double y1, Rgba color) {
  add_rect(s, x0, y0, x1, y1, color, color);
}

// A straight stroke of the given width, antialiased across its length by the shader
// (the quad is one pixel wider on each side for the coverage ramp) and extended by half
// its width past both ends so that strokes meeting at an angle leave no notch.
void add_segment(Shapes& s, Vec2 a, Vec2 b, double width, Rgba color) {
  Vec2 d = b - a;
  const double len = d.norm();
  if (!(len > 0.0)) return;
  d /= len;
  const double half = 0.5 * width, outer = half + 1.0;
  const Vec2 n(-d.y() * outer, d.x() * outer);
  const Vec2 e = d * half;
  const Vec2 p[4] = {a - e + n, b + e + n, b + e - n, a - e - n};
  const float across[4] = {float(outer), float(outer), float(-outer), float(-outer)};
  for (int k : {0, 1, 2, 0, 2, 3})
    s.push_back({float(p[k].x()), float(p[k].y()), color, across[k], float(half)});
}

void add_rect_outline(Shapes& s, double x0, double y0, double x1, double y1, double width,
                      Rgba color) {
  const double h = 0.5 * width;
  add_rect(s, x0 - h, y0 - h, x1 + h, y0 + h, color);
  add_rect(s, x0 - h, y1 - h, x1 + h, y1 + h, color);
  add_rect(s, x0 - h, y0 + h, x0 + h, y1 - h, color);
  add_rect(s, x1 - h, y0 + h, x1 + h, y1 - h, color);
}

// Edges of a triangle list, each once, split into interior ones (two triangles) and the
// boundary (one triangle).
void mesh_edges(const std::vector<std::array<int, 3>>& triangles,
                std::vector<std::pair<int, int>>* interior,
                std::vector<std::pair<int, int>>* boundary) {
  std::vector<std::pair<int, int>> all;
  all.reserve(triangles.size() * 3);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      all.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(all.begin(), all.end());
  interior->clear();
  boundary->clear();
  for (size_t i = 0; i < all.size();) {
    size_t j = i;
    while (j < all.size() && all[j] == all[i]) ++j;
    (j - i == 1 ? boundary : interior)->push_back(all[i]);
    i = j;
  }
}

// det F over a frame's triangles: the extremes and how many are inverted (det F <= 0).
struct DetFSummary {
  double lo = 1.0, hi = 1.0;
  int inverted = 0;
};

DetFSummary summarize_det_f(const FrameState& state) {
  DetFSummary d;
  for (size_t t = 0; t < state.triangles.size(); ++t) {
    const double v = t < state.det_f.size() ? state.det_f[t] : 1.0;
    if (t == 0) d.lo = d.hi = v;
    d.lo = std::min(d.lo, v);
    d.hi = std::max(d.hi, v);
    if (!(v > 0.0)) ++d.inverted;
  }
  return d;
}

// The sloped ground's surface line between pixel columns x0 and x1 (a ground steeper than
// 85 degrees is drawn at 85).
std::pair<Vec2, Vec2> ground_surface(const Camera& cam, const SceneDef& s, double x0, double x1) {
  const Vec2 n = ground_unit_normal(s);
  const double slope = -n.x() / std::max(n.y(), 0.087);  // dy/dx of the surface
  auto at = [&](double px) {
    const double wx = (px - cam.origin.x()) / cam.pixels_per_metre;
    return Vec2(px, cam.to_pixel(Vec2(wx, s.ground_y + slope * wx)).y());
  };
  return {at(x0), at(x1)};
}

// Each plane: a filled half-plane whose surface layer is hatched (res.hatched; the drawing
// convention for a rigid support), so that a large ceiling does not fill the picture with
// stripes; the rest of the half-plane is a plain fill (res.shapes).
void add_plane_fills(FrameVertices& res, const FrameLayout& L, const Camera& cam,
                     const FrameState& state) {
  const double px0 = L.plot.x, px1 = L.plot.x + L.plot.w, py0 = L.plot.y, py1 = L.plot.y + L.plot.h;
  const double band = std::round(std::max(10.0, 30.0 * L.scale));
  if (state.scene.has_ground && ground_is_sloped(state.scene)) {
    // A sloped ground (the course's 4_friction): a plain fill below its surface line.
    const auto [a, b] = ground_surface(cam, state.scene, px0, px1);
    add_triangle(res.shapes, a, b, {px1, std::max(py1, b.y())}, kPlaneFill);
    add_triangle(res.shapes, a, {px1, std::max(py1, b.y())}, {px0, std::max(py1, a.y())},
                 kPlaneFill);
  } else if (state.scene.has_ground) {
    const double gy = cam.to_pixel(Vec2(0.0, state.scene.ground_y)).y();
    const double y_end = std::max(gy, py1), y_band = std::min(gy + band, y_end);
    add_rect(res.hatched, px0, gy, px1, y_band, kPlaneFill);
    add_rect(res.shapes, px0, y_band, px1, y_end, kPlaneFill);
  }
  if (state.scene.has_ceiling) {
    const double cy = cam.to_pixel(Vec2(0.0, state.ceiling_y)).y();
    const double y_end = std::min(py0, cy), y_band = std::max(cy - band, y_end);
    add_rect(res.hatched, px0, y_band, px1, cy, kPlaneFill);
    add_rect(res.shapes, px0, y_end, px1, y_band, kPlaneFill);
  }
}

// Every triangle filled with its det F colour; inverted triangles last: they overlap their
// neighbours (they are folded over), and drawn first they would be hidden under them.
void add_mesh_fills(Shapes& world, const std::vector<Vec2>& p, const FrameState& state,
                    double range) {
  for (const bool inverted_pass : {false, true}) {
    for (size_t t = 0; t < state.triangles.size(); ++t) {
      const double d = t < state.det_f.size() ? state.det_f[t] : 1.0;
      if (!(d > 0.0) != inverted_pass) continue;
      const auto& tri = state.triangles[t];
      add_triangle(world, p[tri[0]], p[tri[1]], p[tri[2]], rgba(det_f_color(d, range)));
    }
  }
}

// The antialiased strokes over the fills: the mesh's interior edges (when `edges`), the
// body's outline and the planes' surfaces.
void add_strokes(FrameVertices& res, const FrameLayout& L, const Camera& cam,
                 const FrameState& state, const std::vector<Vec2>& p, bool edges) {
  const double s = L.scale, px0 = L.plot.x, px1 = L.plot.x + L.plot.w;
  Shapes& world = res.shapes;
  if (state.triangles != res.edges_of) {
    mesh_edges(state.triangles, &res.interior_edges, &res.boundary_edges);
    res.edges_of = state.triangles;
  }
  if (edges) {
    const double w = std::max(1.0, 1.1 * s);
    for (const auto& [a, b] : res.interior_edges) add_segment(world, p[a], p[b], w, kMeshEdge);
  }
  const double outline = std::max(1.25, 1.8 * s);
  for (const auto& [a, b] : res.boundary_edges) add_segment(world, p[a], p[b], outline, kOutline);
  const double plane_line = std::max(1.5, 2.5 * s);
  if (state.scene.has_ground && ground_is_sloped(state.scene)) {
    const auto [a, b] = ground_surface(cam, state.scene, px0 - 10, px1 + 10);
    add_segment(world, a, b, plane_line, kPlaneEdge);
  } else if (state.scene.has_ground) {
    const double gy = cam.to_pixel(Vec2(0.0, state.scene.ground_y)).y();
    add_segment(world, {px0 - 10, gy + 0.5 * plane_line}, {px1 + 10, gy + 0.5 * plane_line},
                plane_line, kPlaneEdge);
  }
  if (state.scene.has_ceiling) {
    const double cy = cam.to_pixel(Vec2(0.0, state.ceiling_y)).y();
    add_segment(world, {px0 - 10, cy - 0.5 * plane_line}, {px1 + 10, cy - 0.5 * plane_line},
                plane_line, kPlaneEdge);
  }
}

// A ring of `segments` strokes around `c`.
void add_ring(Shapes& s, Vec2 c, double radius, double width, Rgba color) {
  constexpr int kSegments = 24;
  for (int k = 0; k < kSegments; ++k) {
    const double a0 = 2.0 * M_PI * k / kSegments, a1 = 2.0 * M_PI * (k + 1) / kSegments;
    add_segment(s, c + radius * Vec2(std::cos(a0), std::sin(a0)),
                c + radius * Vec2(std::cos(a1), std::sin(a1)), width, color);
  }
}

// A ring around every inverted triangle (det F <= 0), dark under green as in the study's
// contact sheet: a folded sliver a pixel wide is still found at a glance.
void add_inverted_rings(Shapes& world, const std::vector<Vec2>& p, const FrameState& state,
                        double s) {
  // Around the centroid, a little larger than the triangle but never a ring that hides
  // the body (a folded sliver can be long).
  const double min_radius = std::max(5.0, 7.0 * s), max_radius = std::max(8.0, 14.0 * s);
  for (size_t t = 0; t < state.triangles.size() && t < state.det_f.size(); ++t) {
    if (state.det_f[t] > 0.0) continue;
    const auto& tri = state.triangles[t];
    const Vec2 c = (p[tri[0]] + p[tri[1]] + p[tri[2]]) / 3.0;
    double r = min_radius;
    for (int k = 0; k < 3; ++k) r = std::max(r, (p[tri[k]] - c).norm() + 3.0 * s);
    r = std::min(r, max_radius);
    add_ring(world, c, r, std::max(2.0, 3.2 * s), kOutline);
    add_ring(world, c, r, std::max(1.2, 1.8 * s), rgba(kInvertedColor));
  }
}

// The side panel: scene, model, Lame parameters, time, step, det F extremes, and the
// colour bar with its ticks, the min/max markers and the det F <= 0 swatch.
// Returns the end of its opaque backdrop in res.shapes (what can be drawn without blending).
size_t draw_panel(FrameVertices& res, const FrameLayout& L, const FrameState& state, double det_lo,
                  double det_hi, int inverted, const DrawOptions& o) {
  const SceneDef& scene = state.scene;
  const double s = L.scale;
  const double range = o.color_range;
  Shapes& panel = res.shapes;
  Rgba backdrop = kPanelBackground;
  if (L.overlay) backdrop.a = 0.86f;
  add_rect(panel, L.panel.x, 0, L.panel.x + L.panel.w, L.height, backdrop);
  add_rect(panel, L.panel.x, 0, L.panel.x + std::max(1.0, std::round(s)), L.height, kSeparator);
  const size_t backdrop_end = panel.size();
  const double pad = std::round(26.0 * s);
  const double x0 = L.panel.x + pad;
  const double body = res.font_sizes[kBody], small = res.font_sizes[kSmall];
  double y = pad + res.atlas->ascent(kTitle);
  res.add_text(scene.name, kTitle, x0, y, kInk);
  y += 1.25 * body;
  if (scene.has_mass_spring) {  // the course's springs: their stiffness, no Lame parameters
    res.add_text("mass-spring", kBody, x0, y, kMutedInk);
    y += 1.3 * body;
    res.add_text("k = " + format_si(scene.spring_stiffness, "N/m"), kBody, x0, y, kMutedInk);
    y += 1.3 * body;
  } else {
    res.add_text(model_display_name(scene.model), kBody, x0, y, kMutedInk);
    y += 1.3 * body;
    res.add_text("μ = " + format_si(scene.lame.mu, "Pa"), kBody, x0, y, kMutedInk);
    y += 1.3 * body;
    res.add_text("λ = " + format_si(scene.lame.lambda, "Pa"), kBody, x0, y, kMutedInk);
  }
  y += 2.0 * body;
  res.add_text(format_time(state.time, scene.h), kBody, x0, y, kInk);
  y += 1.3 * body;
  res.add_text("step " + std::to_string(state.step), kBody, x0, y, kInk);
  y += 2.0 * body;
  char buf[64];
  std::snprintf(buf, sizeof buf, "min det F = %.3f", det_lo);
  res.add_text(buf, kBody, x0, y, kInk);
  y += 1.3 * body;
  std::snprintf(buf, sizeof buf, "max det F = %.3f", det_hi);
  res.add_text(buf, kBody, x0, y, kInk);
  if (inverted > 0) {
    y += 1.3 * body;
    res.add_text(
        "inverted: " + std::to_string(inverted) + (inverted == 1 ? " triangle" : " triangles"),
        kBody, x0, y, kInvertedInk);
  }

  // Colour bar: vertical, stretch up, with the det F <= 0 swatch below it.
  const double bar_w = std::round(24.0 * s), marker = std::round(9.0 * s);
  const double bar_x0 = x0 + marker + std::round(4.0 * s), bar_x1 = bar_x0 + bar_w;
  const double swatch_h = std::round(20.0 * s);
  const double swatch_y1 = L.height - pad, swatch_y0 = swatch_y1 - swatch_h;
  const double bar_y1 = std::round(swatch_y0 - 1.6 * small);
  const double bar_title_y = y + 2.0 * body;
  const double bar_y0 = std::round(bar_title_y + 1.15 * small + 0.9 * small);
  // What det F is, and which scale: the fixed one or one chosen from the data.
  res.add_text(o.color_range_auto ? "det F (auto scale)" : "det F", kBody, x0, bar_title_y, kInk);
  res.add_text("= area now / area at rest", kSmall, x0, bar_title_y + 1.15 * small, kMutedInk);
  const auto bar_y = [&](double t) { return bar_y1 - 0.5 * (t + 1.0) * (bar_y1 - bar_y0); };
  for (int k = 0; k < 6; ++k) {  // the colormap's seven stops: piecewise linear, exact
    const double t0 = -1.0 + k / 3.0, t1 = -1.0 + (k + 1) / 3.0;
    add_rect(panel, bar_x0, bar_y(t1), bar_x1, bar_y(t0), rgba(diverging_color(t1)),
             rgba(diverging_color(t0)));
  }
  const double thin = std::max(1.0, std::round(s));
  add_rect_outline(panel, bar_x0, bar_y0, bar_x1, bar_y1, thin, kMutedInk);
  const double tick_len = std::round(6.0 * s), label_x = bar_x1 + tick_len + std::round(6.0 * s);
  double label_right = label_x;
  for (const ColorBarTick& t : color_bar_ticks(range)) {
    const double ty = std::round(bar_y(t.position));
    add_rect(panel, bar_x1, ty - 0.5 * thin, bar_x1 + tick_len, ty + 0.5 * thin, kMutedInk);
    res.add_text(t.label, kSmall, label_x, ty + 0.36 * small, kInk);
    label_right = std::max(label_right, label_x + res.atlas->text_width(t.label, kSmall));
  }
  const double note_x = label_right + std::round(14.0 * s);
  add_rect(panel, bar_x0, swatch_y0, bar_x1, swatch_y1, rgba(kInvertedColor));
  add_rect_outline(panel, bar_x0, swatch_y0, bar_x1, swatch_y1, thin, kMutedInk);
  res.add_text("det F ≤ 0 (ringed)", kSmall, label_x, 0.5 * (swatch_y0 + swatch_y1) + 0.36 * small,
               kInk);
  // Markers (a glyph, so antialiased like the text) at the current min and max det F,
  // beside the swatch when inverted, each labelled "min 0.842" / "max 1.04" right of the
  // ticks: the max label at or above the min label, a line apart at least.
  const auto marker_y = [&](double d) {
    return d > 0.0 ? bar_y(det_f_scale_position(d, range)) : 0.5 * (swatch_y0 + swatch_y1);
  };
  const double line = 1.15 * small;
  double max_label_y = marker_y(det_hi), min_label_y = marker_y(det_lo);
  if (min_label_y - max_label_y < line) {
    const double mid = 0.5 * (min_label_y + max_label_y);
    max_label_y = mid - 0.5 * line;
    min_label_y = mid + 0.5 * line;
  }
  for (const double d : {det_lo, det_hi}) {
    const double mx = bar_x0 - std::round(2.0 * s) - res.atlas->text_width("▶", kSmall);
    res.add_text("▶", kSmall, mx, marker_y(d) - res.atlas->ink_middle(kSmall, U'▶'), kInk);
  }
  char label[48];
  std::snprintf(label, sizeof label, "max %.3f", det_hi);
  res.add_text(label, kSmall, note_x, max_label_y + 0.36 * small, kInk);
  if (det_lo > 0.0) {  // (an inverted min points at the swatch, which says so)
    std::snprintf(label, sizeof label, "min %.3f", det_lo);
    res.add_text(label, kSmall, note_x, min_label_y + 0.36 * small, kInk);
  } else {
    min_label_y = -1e9;
  }
  // The ends' meaning, where no marker label is.
  const auto clear_of_labels = [&](double y) {
    return std::abs(y - max_label_y) >= line && std::abs(y - min_label_y) >= line;
  };
  if (clear_of_labels(bar_y(1.0)))
    res.add_text("stretch", kSmall, note_x, bar_y(1.0) + 0.36 * small, kMutedInk);
  if (clear_of_labels(bar_y(-1.0)))
    res.add_text("compression", kSmall, note_x, bar_y(-1.0) + 0.36 * small, kMutedInk);
  return backdrop_end;
}

}  // namespace

void FrameVertices::add_text(std::string_view s, int size, double x, double baseline, Rgba color,
                             double align) {
  if (align != 0.0) x -= align * atlas->text_width(s, size);
  glyphs.clear();
  atlas->layout(s, size, x, baseline, &glyphs);
  for (const GlyphQuad& q : glyphs) {
    const TextVertex v00{q.x0, q.y0, q.u0, q.v0, color}, v10{q.x1, q.y0, q.u1, q.v0, color};
    const TextVertex v11{q.x1, q.y1, q.u1, q.v1, color}, v01{q.x0, q.y1, q.u0, q.v1, color};
    text.insert(text.end(), {v00, v10, v11, v00, v11, v01});
  }
}

ShapeRanges build_frame_vertices(FrameVertices& v, const FrameState& state, const FrameLayout& L,
                                 const Camera& cam, const DrawOptions& options) {
  v.shapes.clear();
  v.hatched.clear();
  v.text.clear();
  // The world (clipped to the plot area when drawn), then the panel (not clipped).
  const int nodes = static_cast<int>(state.x.size() / 2);
  std::vector<Vec2> p(static_cast<size_t>(nodes));
  for (int i = 0; i < nodes; ++i) p[i] = cam.to_pixel(Vec2(state.x[2 * i], state.x[2 * i + 1]));
  add_plane_fills(v, L, cam, state);
  add_mesh_fills(v.shapes, p, state, options.color_range);
  ShapeRanges ranges;
  ranges.world_fills = v.shapes.size();
  add_strokes(v, L, cam, state, p, options.edges);
  if (options.ring_inverted) add_inverted_rings(v.shapes, p, state, L.scale);
  ranges.world_end = v.shapes.size();
  const DetFSummary det = summarize_det_f(state);
  ranges.panel_backdrop = options.panel
                              ? draw_panel(v, L, state, det.lo, det.hi, det.inverted, options)
                              : ranges.world_end;
  return ranges;
}

}  // namespace invfree::render
