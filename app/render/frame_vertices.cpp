#include "app/render/frame_vertices.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/render/field_legend.h"
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
constexpr Rgba kSelectedInk{1.0f, 0.86f, 0.0f, 1.0f};   // the selected triangle's outline
constexpr Rgba kTensionInk{0.80f, 0.04f, 0.10f, 1.0f};  // stress glyphs
constexpr Rgba kCompressionInk{0.04f, 0.26f, 0.78f, 1.0f};
constexpr Rgba kGlyphHalo{1.0f, 1.0f, 1.0f, 0.85f};

// The longest stress glyph stroke, as a fraction of the glyph spacing (the mean triangle's
// size, or the thinning cell).
constexpr double kGlyphLength = 0.85;

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

// Every triangle filled with its det F colour, or with its field's colour on `field`
// (when set); inverted triangles last: they overlap their neighbours (they are folded
// over), and drawn first they would be hidden under them.
void add_mesh_fills(Shapes& world, const std::vector<Vec2>& p, const FrameState& state,
                    double range, const FieldScale* field) {
  for (const bool inverted_pass : {false, true}) {
    for (size_t t = 0; t < state.triangles.size(); ++t) {
      const double d = t < state.det_f.size() ? state.det_f[t] : 1.0;
      if (!(d > 0.0) != inverted_pass) continue;
      const auto& tri = state.triangles[t];
      const Rgb c = field ? field_color(*field, state.field[t]) : det_f_color(d, range);
      add_triangle(world, p[tri[0]], p[tri[1]], p[tri[2]], rgba(c));
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

// The inverted triangles' mark (det F <= 0), over their green fill: each one's own edges
// as a dark stroke, and a ring, dark under green as in the study's contact sheet, only
// around one too small to be seen (a folded sliver a pixel wide is still found at a
// glance), and no ring that would overlap one already drawn: where many triangles invert
// (linear elasticity squashed) rings around each one hid the body under a tangle of
// circles, while the outlined green fills show where, and how much, it inverted.
void add_inverted_rings(Shapes& world, const std::vector<Vec2>& p, const FrameState& state,
                        double s) {
  // Around the centroid, a little larger than the triangle but never a ring that hides
  // the body (a folded sliver can be long).
  const double min_radius = std::max(5.0, 7.0 * s), max_radius = std::max(8.0, 14.0 * s);
  const double visible_area = 0.5 * min_radius * min_radius;  // pixels^2
  std::vector<std::pair<Vec2, double>> rings;
  for (size_t t = 0; t < state.triangles.size() && t < state.det_f.size(); ++t) {
    if (state.det_f[t] > 0.0) continue;
    const auto& tri = state.triangles[t];
    for (int k = 0; k < 3; ++k)
      add_segment(world, p[tri[k]], p[tri[(k + 1) % 3]], std::max(1.0, 1.4 * s), kOutline);
    const Vec2 e1 = p[tri[1]] - p[tri[0]], e2 = p[tri[2]] - p[tri[0]];
    if (0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x()) >= visible_area) continue;
    const Vec2 c = (p[tri[0]] + p[tri[1]] + p[tri[2]]) / 3.0;
    double r = min_radius;
    for (int k = 0; k < 3; ++k) r = std::max(r, (p[tri[k]] - c).norm() + 3.0 * s);
    r = std::min(r, max_radius);
    bool overlaps = false;
    for (const auto& [c2, r2] : rings) overlaps = overlaps || (c - c2).norm() < r + r2;
    if (overlaps) continue;
    rings.emplace_back(c, r);
    add_ring(world, c, r, std::max(2.0, 3.2 * s), kOutline);
    add_ring(world, c, r, std::max(1.2, 1.8 * s), rgba(kInvertedColor));
  }
}

// A failed run's last frame: a red border around the world and, at its top, a red banner
// with the failure in white, cut to the world's width.
constexpr Rgba kFailureInk{0.80f, 0.04f, 0.06f, 1.0f};
// `text` cut with an ellipsis to `room` pixels at font `size` (whole UTF-8 characters).
std::string fit_text(const FrameVertices& res, std::string text, int size, double room) {
  if (res.atlas->text_width(text, size) <= room) return text;
  while (text.size() > 12 && res.atlas->text_width(text + "…", size) > room) {
    while (!text.empty() && (static_cast<unsigned char>(text.back()) & 0xC0) == 0x80)
      text.pop_back();  // a whole UTF-8 character: its continuation bytes, then its lead
    text.pop_back();
  }
  return text + "…";
}

// A titled view's heading (DrawOptions::title): a light band across the plot's top with a
// thin rule under it, the first line in the body font, the others small.
constexpr Rgba kTitleBand{1.0f, 1.0f, 1.0f, 0.94f};
void add_title(FrameVertices& res, const FrameLayout& L, const std::vector<std::string>& title) {
  const double s = L.scale, x0 = L.plot.x, y0 = L.plot.y, x1 = L.plot.x + L.plot.w;
  const double band = title_band_height(L);
  add_rect(res.shapes, x0, y0, x1, y0 + band, kTitleBand);
  add_rect(res.shapes, x0, y0 + band - std::max(1.0, std::round(1.5 * s)), x1, y0 + band,
           kMutedInk);
  const double pad = std::round(14.0 * s), room = (x1 - x0) - 2.0 * pad;
  for (size_t k = 0; k < title.size() && k < 2; ++k) {
    const int size = k == 0 ? kBody : kSmall;
    res.add_text(fit_text(res, title[k], size, room), size, x0 + pad,
                 y0 + (k == 0 ? 0.42 : 0.82) * band, k == 0 ? kInk : kMutedInk);
  }
}

// top: the heading band's height above the banner (0: none).
void add_failure_mark(FrameVertices& res, const FrameLayout& L, const std::string& failure,
                      double top) {
  const double s = L.scale, x0 = L.plot.x, y0 = L.plot.y, x1 = L.plot.x + L.plot.w,
               y1 = L.plot.y + L.plot.h;
  const double border = std::max(3.0, std::round(6.0 * s));
  add_rect(res.shapes, x0, y0, x1, y0 + border, kFailureInk);
  add_rect(res.shapes, x0, y1 - border, x1, y1, kFailureInk);
  add_rect(res.shapes, x0, y0, x0 + border, y1, kFailureInk);
  add_rect(res.shapes, x1 - border, y0, x1, y1, kFailureInk);
  const double body = res.font_sizes[kBody];
  const double banner = std::round(1.9 * body);
  add_rect(res.shapes, x0, y0 + top, x1, y0 + top + banner, kFailureInk);
  const double pad = std::round(14.0 * s), room = (x1 - x0) - 2.0 * pad;
  res.add_text(fit_text(res, "RUN FAILED: " + failure, kBody, room), kBody, x0 + pad,
               y0 + top + 0.5 * banner + 0.36 * body, Rgba{1.0f, 1.0f, 1.0f, 1.0f});
}

// A filled disk antialiased as the strokes are: a fan of wedges whose `across` runs from 0
// at the centre to radius + 1 at the rim, so the shader's coverage ramp falls off over the
// last pixel (exact along each spoke; the chords' midpoints lie within (r + 1)(1 - cos(pi /
// segments)) of the true distance, a twentieth of a pixel at 10 pixels).
void add_dot(Shapes& s, Vec2 c, double radius, Rgba color) {
  if (!(radius > 0.0) || !std::isfinite(c.x()) || !std::isfinite(c.y())) return;
  const double outer = radius + 1.0;
  const int segments = std::clamp(static_cast<int>(std::ceil(2.0 * M_PI * outer / 3.0)), 12, 64);
  const float half = float(radius);
  for (int k = 0; k < segments; ++k) {
    const double a0 = 2.0 * M_PI * k / segments, a1 = 2.0 * M_PI * (k + 1) / segments;
    const Vec2 p0 = c + outer * Vec2(std::cos(a0), std::sin(a0));
    const Vec2 p1 = c + outer * Vec2(std::cos(a1), std::sin(a1));
    s.push_back({float(c.x()), float(c.y()), color, 0.0f, half});
    s.push_back({float(p0.x()), float(p0.y()), color, float(outer), half});
    s.push_back({float(p1.x()), float(p1.y()), color, float(outer), half});
  }
}

// The overlays (FrameState::overlays), each its segments' strokes and then its dots over
// them, in order.
void add_overlays(Shapes& world, const FrameState& state, const Camera& cam, double s) {
  for (const Overlay& o : state.overlays) {
    const Rgba color = rgba(o.color);
    const size_t n = o.points.size();
    const double width = std::max(1.0, o.stroke_width * s);
    for (const auto& [a, b] : o.segments) {
      if (a < 0 || b < 0 || static_cast<size_t>(a) >= n || static_cast<size_t>(b) >= n) continue;
      const Vec2 pa = cam.to_pixel(o.points[static_cast<size_t>(a)]);
      const Vec2 pb = cam.to_pixel(o.points[static_cast<size_t>(b)]);
      if (pa.allFinite() && pb.allFinite()) add_segment(world, pa, pb, width, color);
    }
    if (!(o.dot_radius > 0.0)) continue;
    const double r = std::max(kMinOverlayDotPixels * s, o.dot_radius * cam.pixels_per_metre);
    for (const Vec2& p : o.points) add_dot(world, cam.to_pixel(p), r, color);
  }
}

// The principal stress glyphs: per triangle a cross of two strokes centred at its
// centroid along its principal directions, each as long as its stress's magnitude relative
// to the frame's largest (kGlyphLength of the spacing for that one), tension red and
// compression blue, over a white halo so that they read on any fill. Readable only where
// they do not overlap: when the mean triangle is smaller than a glyph cell
// (kGlyphCellPixels, scaled), one glyph per cell of a pixel grid over the plot, for the
// triangle whose centroid lies nearest the cell's middle.
void add_stress_glyphs(FrameVertices& res, const std::vector<Vec2>& p, const FrameState& state,
                       const FrameLayout& L) {
  const size_t n = state.triangles.size();
  if (n == 0 || state.principal_stress.size() != n || state.principal_direction.size() != n) return;
  Shapes& world = res.shapes;
  double max_abs = 0.0, area = 0.0;
  std::vector<Vec2>& centroids = res.glyph_centroids;
  centroids.resize(n);
  for (size_t t = 0; t < n; ++t) {
    const auto& tri = state.triangles[t];
    const Vec2 a = p[tri[0]], b = p[tri[1]], c = p[tri[2]];
    centroids[t] = (a + b + c) / 3.0;
    const Vec2 u = b - a, v = c - a;
    area += 0.5 * std::abs(u.x() * v.y() - u.y() * v.x());
    const Vec2& s = state.principal_stress[t];
    if (std::isfinite(s.x()) && std::isfinite(s.y()))
      max_abs = std::max({max_abs, std::abs(s.x()), std::abs(s.y())});
  }
  if (!(max_abs > 0.0)) return;
  const double cell = glyph_cell_pixels(L.scale);
  const double size = std::sqrt(area / static_cast<double>(n));  // the mean triangle's
  const bool thinned = size < cell;
  const double max_length = kGlyphLength * (thinned ? cell : size);
  // Thinned: the triangle nearest each cell's middle.
  std::vector<int>& chosen = res.glyph_chosen;
  chosen.clear();
  if (thinned) {
    const int cols = std::max(1, static_cast<int>(std::ceil(L.plot.w / cell)));
    const int rows = std::max(1, static_cast<int>(std::ceil(L.plot.h / cell)));
    std::vector<int>& best = res.glyph_cell_best;
    std::vector<double>& best_d = res.glyph_cell_distance;
    best.assign(static_cast<size_t>(cols) * rows, -1);
    best_d.assign(best.size(), 0.0);
    for (size_t t = 0; t < n; ++t) {
      const double fx = (centroids[t].x() - L.plot.x) / cell;
      const double fy = (centroids[t].y() - L.plot.y) / cell;
      if (!(fx >= 0.0 && fy >= 0.0 && fx < cols && fy < rows)) continue;
      const int cx = static_cast<int>(fx), cy = static_cast<int>(fy);
      const double d = std::hypot(fx - cx - 0.5, fy - cy - 0.5);
      const size_t k = static_cast<size_t>(cy) * cols + cx;
      if (best[k] < 0 || d < best_d[k]) {
        best[k] = static_cast<int>(t);
        best_d[k] = d;
      }
    }
    for (const int t : best)
      if (t >= 0) chosen.push_back(t);
  } else {
    for (size_t t = 0; t < n; ++t) chosen.push_back(static_cast<int>(t));
  }
  const double width = std::max(1.6, 2.4 * L.scale), halo = width + std::max(2.0, 2.4 * L.scale);
  for (const bool halo_pass : {true, false}) {
    for (const int t : chosen) {
      const Vec2 s = state.principal_stress[static_cast<size_t>(t)];
      const Vec2 dir = state.principal_direction[static_cast<size_t>(t)];
      const Vec2 d1(dir.x(), -dir.y());  // world y up, pixels y down
      const Vec2 d2(-d1.y(), d1.x());
      for (int k = 0; k < 2; ++k) {
        const double value = s(k);
        if (!std::isfinite(value)) continue;
        const double half = 0.5 * max_length * std::abs(value) / max_abs;
        if (half < 0.5) continue;  // under a pixel: nothing to read
        const Vec2 d = k == 0 ? d1 : d2, c = centroids[static_cast<size_t>(t)];
        if (halo_pass)
          add_segment(world, c - half * d, c + half * d, halo, kGlyphHalo);
        else
          add_segment(world, c - half * d, c + half * d, width,
                      value > 0.0 ? kTensionInk : kCompressionInk);
      }
    }
  }
}

// The selected triangle's outline: a wide dark stroke under a bright yellow one, so that it
// shows on every colour scale (no scale has this yellow next to black).
void add_selected_outline(Shapes& world, const std::vector<Vec2>& p, const FrameState& state,
                          int selected, double s) {
  if (selected < 0 || static_cast<size_t>(selected) >= state.triangles.size()) return;
  const auto& tri = state.triangles[static_cast<size_t>(selected)];
  for (const auto& [width, color] : {std::pair{std::max(5.0, 6.5 * s), kOutline},
                                     std::pair{std::max(2.5, 3.0 * s), kSelectedInk}})
    for (int k = 0; k < 3; ++k) add_segment(world, p[tri[k]], p[tri[(k + 1) % 3]], width, color);
}

// A colour bar's ticks, right of the bar at bar_x1, each labelled; `bar_y` maps a tick's
// position on the scale to its pixel row.
struct BarTickLabels {
  double label_x;  // where the labels start
  double note_x;   // where notes right of the longest label start
};
template <class Tick, class BarY>
BarTickLabels add_bar_ticks(FrameVertices& res, const std::vector<Tick>& ticks, double bar_x1,
                            double s, double thin, const BarY& bar_y) {
  const double small = res.font_sizes[kSmall];
  const double tick_len = std::round(6.0 * s), label_x = bar_x1 + tick_len + std::round(6.0 * s);
  double label_right = label_x;
  for (const Tick& t : ticks) {
    const double ty = std::round(bar_y(t.position));
    add_rect(res.shapes, bar_x1, ty - 0.5 * thin, bar_x1 + tick_len, ty + 0.5 * thin, kMutedInk);
    res.add_text(t.label, kSmall, label_x, ty + 0.36 * small, kInk);
    label_right = std::max(label_right, label_x + res.atlas->text_width(t.label, kSmall));
  }
  return {label_x, label_right + std::round(14.0 * s)};
}

// The colour bar of a field other than det F, laid out as det F's below the panel's text:
// its title and what it is (field_legend.h, wrapped to the panel), the bar of its scale
// (app/field_colormap.h) with round ticks, markers at the frame's min and max (Psi,
// stress) or each category's triangle count (clamped), and below it a ring, for inverted
// triangles are ringed in every colouring.
void draw_field_bar(FrameVertices& res, const FrameLayout& L, const FieldScale& scale,
                    const FieldStats& stats, bool mass_spring, double x0, double y, double pad) {
  const double s = L.scale;
  Shapes& panel = res.shapes;
  const double body = res.font_sizes[kBody], small = res.font_sizes[kSmall];
  const double bar_w = std::round(24.0 * s), marker = std::round(9.0 * s);
  const double bar_x0 = x0 + marker + std::round(4.0 * s), bar_x1 = bar_x0 + bar_w;
  const double swatch_h = std::round(20.0 * s);
  const double swatch_y1 = L.height - pad, swatch_y0 = swatch_y1 - swatch_h;
  const double bar_y1 = std::round(swatch_y0 - 1.6 * small);
  const double bar_title_y = y + 2.0 * body;
  FieldLegendWords words = field_legend_words(scale);
  // The course's springs have no energy or stress per triangle: the field is 0 there.
  if (mass_spring) words.subtitle += "\nmass-spring: none (0)";
  const FieldUnit unit = field_unit(scale);
  res.add_text(words.title, kBody, x0, bar_title_y, kInk);
  const double text_width = L.panel.x + L.panel.w - 0.5 * pad - x0;
  double line_y = bar_title_y;
  for (const std::string& line : wrap_words(words.subtitle, text_width, [&](const std::string& t) {
         return res.atlas->text_width(t, kSmall);
       })) {
    line_y += 1.15 * small;
    res.add_text(line, kSmall, x0, line_y, kMutedInk);
  }
  const double bar_y0 = std::round(line_y + 0.9 * small);
  const auto bar_y = [&](double t) { return bar_y1 - t * (bar_y1 - bar_y0); };  // t: 0..1
  const double thin = std::max(1.0, std::round(s));
  switch (scale.field) {
    case TriangleField::Psi:  // the scale's stops: piecewise linear, exact
      for (int k = 0; k + 1 < kSequentialStops; ++k) {
        const double t0 = double(k) / (kSequentialStops - 1),
                     t1 = double(k + 1) / (kSequentialStops - 1);
        add_rect(panel, bar_x0, bar_y(t1), bar_x1, bar_y(t0), rgba(sequential_color(t1)),
                 rgba(sequential_color(t0)));
      }
      break;
    case TriangleField::Stress:
      for (int k = 0; k < 6; ++k) {
        const double t0 = k / 6.0, t1 = (k + 1) / 6.0;
        add_rect(panel, bar_x0, bar_y(t1), bar_x1, bar_y(t0), rgba(diverging_color(2 * t1 - 1)),
                 rgba(diverging_color(2 * t0 - 1)));
      }
      break;
    case TriangleField::Clamped:
      for (int k = 0; k < kClampedCategories; ++k) {
        const double t0 = double(k) / kClampedCategories, t1 = double(k + 1) / kClampedCategories;
        add_rect(panel, bar_x0, bar_y(t1), bar_x1, bar_y(t0), rgba(clamped_color(k)));
        if (k > 0)
          add_rect(panel, bar_x0, bar_y(t0) - 0.5 * thin, bar_x1, bar_y(t0) + 0.5 * thin,
                   kMutedInk);
      }
      break;
    case TriangleField::DetF:
      break;
  }
  add_rect_outline(panel, bar_x0, bar_y0, bar_x1, bar_y1, thin, kMutedInk);
  const BarTickLabels ticks = add_bar_ticks(res, field_bar_ticks(scale), bar_x1, s, thin, bar_y);
  const double label_x = ticks.label_x, note_x = ticks.note_x;
  // The ring legend: the inverted triangles' mark, whatever the colouring.
  const Vec2 ring_centre(0.5 * (bar_x0 + bar_x1), 0.5 * (swatch_y0 + swatch_y1));
  const double ring_r = 0.42 * swatch_h;
  add_ring(panel, ring_centre, ring_r, std::max(2.0, 3.2 * s), kOutline);
  add_ring(panel, ring_centre, ring_r, std::max(1.2, 1.8 * s), rgba(kInvertedColor));
  res.add_text("det F ≤ 0 (ringed)", kSmall, label_x, ring_centre.y() + 0.36 * small, kInk);
  if (scale.field == TriangleField::Clamped) {  // how many triangles in each category
    for (int k = 0; k < kClampedCategories; ++k) {
      const int n = stats.category_counts[k];
      const double ty = bar_y((k + 0.5) / kClampedCategories);
      // 0 clamped: Newton's Hessian is the true one there.
      std::string note = n == 0   ? "none"
                         : k == 0 ? std::to_string(n) + ", Hessian exact"
                                  : std::to_string(n) + (n == 1 ? " triangle" : " triangles");
      res.add_text(note, kSmall, note_x, ty + 0.36 * small, n == 0 ? kMutedInk : kInk);
    }
    return;
  }
  if (stats.count == 0) return;
  // Markers at the frame's min and max, each labelled right of the ticks, the max label at
  // or above the min label, a line apart at least (as det F's).
  const double line = 1.15 * small;
  double max_label_y = bar_y(field_bar_position(scale, stats.max));
  double min_label_y = bar_y(field_bar_position(scale, stats.min));
  if (min_label_y - max_label_y < line) {
    const double mid = 0.5 * (min_label_y + max_label_y);
    max_label_y = mid - 0.5 * line;
    min_label_y = mid + 0.5 * line;
  }
  for (const double v : {stats.min, stats.max}) {
    const double mx = bar_x0 - std::round(2.0 * s) - res.atlas->text_width("▶", kSmall);
    res.add_text("▶", kSmall, mx,
                 bar_y(field_bar_position(scale, v)) - res.atlas->ink_middle(kSmall, U'▶'), kInk);
  }
  // Psi's with their own prefix (its ticks have theirs), stress's in the bar's unit.
  const auto value_text = [&](double v) {
    return scale.field == TriangleField::Psi ? format_si(v, "Pa") : format_in_unit(v, unit);
  };
  res.add_text("max " + value_text(stats.max), kSmall, note_x, max_label_y + 0.36 * small, kInk);
  res.add_text("min " + value_text(stats.min), kSmall, note_x, min_label_y + 0.36 * small, kInk);
  const auto clear_of_labels = [&](double y) {
    return std::abs(y - max_label_y) >= line && std::abs(y - min_label_y) >= line;
  };
  if (!words.top_note.empty() && clear_of_labels(bar_y(1.0)))
    res.add_text(words.top_note, kSmall, note_x, bar_y(1.0) + 0.36 * small, kMutedInk);
  if (!words.bottom_note.empty() && clear_of_labels(bar_y(0.0)))
    res.add_text(words.bottom_note, kSmall, note_x, bar_y(0.0) + 0.36 * small, kMutedInk);
}

// The side panel: scene, model, Lame parameters, time, step, det F extremes, and the
// colour bar with its ticks, the min/max markers and the det F <= 0 swatch.
// Returns the end of its opaque backdrop in res.shapes (what can be drawn without blending).
size_t draw_panel(FrameVertices& res, const FrameLayout& L, const FrameState& state, double det_lo,
                  double det_hi, int inverted, const DrawOptions& o, const FieldScale* field,
                  const FieldStats& field_stats) {
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
  const bool lone_particles = state.triangles.empty() &&
                              (state.overlays.empty() || state.overlays.front().segments.empty());
  if (lone_particles) {  // (the course's free fall: no springs, no material)
    res.add_text("particles", kBody, x0, y, kMutedInk);
    y += 1.3 * body;
  } else if (scene.has_mass_spring) {  // the course's springs: their stiffness, no Lame parameters
    res.add_text("mass-spring", kBody, x0, y, kMutedInk);
    y += 1.3 * body;
    res.add_text("k = " + format_si(scene.spring_stiffness, "N/m"), kBody, x0, y, kMutedInk);
    y += 1.3 * body;
  } else {
    res.add_text(model_display_name(scene.model), kBody, x0, y, kMutedInk);
    y += 1.3 * body;
    // A body with its own material: the scene's μ and λ may be used by none, so each
    // body's (up to three; more say only that they differ).
    const int bodies = body_count(scene);
    bool per_body = false;
    for (const BodyDef& b : scene.bodies) per_body = per_body || b.lame.has_value();
    if (!per_body) {
      res.add_text("μ = " + format_si(scene.lame.mu, "Pa"), kBody, x0, y, kMutedInk);
      y += 1.3 * body;
      res.add_text("λ = " + format_si(scene.lame.lambda, "Pa"), kBody, x0, y, kMutedInk);
    } else if (bodies <= 3) {
      for (int k = 0; k < bodies; ++k) {
        const Lame lame = placed_body(scene, k).lame;
        res.add_text("body " + std::to_string(k + 1) + ": μ " + format_si(lame.mu, "Pa") + ", λ " +
                         format_si(lame.lambda, "Pa"),
                     kSmall, x0, y, kMutedInk);
        if (k + 1 < bodies) y += 1.25 * small;
      }
    } else {
      res.add_text("μ, λ: per body (" + std::to_string(bodies) + " bodies)", kBody, x0, y,
                   kMutedInk);
    }
  }
  if (!lone_particles) {  // which of the lecture's methods steps it
    for (const std::string& line : method_lines(scene)) {
      y += 1.3 * body;
      res.add_text(line, kSmall, x0, y, kMutedInk);
    }
  }
  if (body_count(scene) > 1 && scene.self_contact_on()) {  // what acts between the bodies
    char buf[64];
    std::snprintf(buf, sizeof buf, "between bodies: friction μ = %.2g", scene.self_friction);
    y += 1.3 * body;
    res.add_text(scene.self_friction > 0.0 ? buf : "between bodies: no friction", kSmall, x0, y,
                 kMutedInk);
  }
  y += 2.0 * body;
  res.add_text(format_time(state.time, scene.h), kBody, x0, y, kInk);
  y += 1.3 * body;
  res.add_text("step " + std::to_string(state.step), kBody, x0, y, kInk);
  y += 2.0 * body;
  if (state.triangles.empty()) {
    // Particles only (the course's chapter 0): no det F, no field, no colour bar; how many
    // particles and springs (the first overlay's) instead.
    const size_t nodes = state.x.size() / 2;
    const size_t springs = state.overlays.empty() ? 0 : state.overlays.front().segments.size();
    res.add_text("no triangles", kBody, x0, y, kMutedInk);
    y += 1.3 * body;
    res.add_text(std::to_string(nodes) + (nodes == 1 ? " particle" : " particles"), kBody, x0, y,
                 kInk);
    if (springs > 0) {
      y += 1.3 * body;
      res.add_text(std::to_string(springs) + (springs == 1 ? " spring" : " springs"), kBody, x0, y,
                   kInk);
    }
    return backdrop_end;
  }
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

  if (field) {  // another field's bar in place of det F's
    draw_field_bar(res, L, *field, field_stats, !scene.has_triangle_elasticity(), x0, y, pad);
    return backdrop_end;
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
  const BarTickLabels ticks = add_bar_ticks(res, color_bar_ticks(range), bar_x1, s, thin, bar_y);
  const double label_x = ticks.label_x, note_x = ticks.note_x;
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
  words.emplace_back(s);
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
  v.words.clear();
  // The world (clipped to the plot area when drawn), then the panel (not clipped).
  const int nodes = static_cast<int>(state.x.size() / 2);
  std::vector<Vec2> p(static_cast<size_t>(nodes));
  for (int i = 0; i < nodes; ++i) p[i] = cam.to_pixel(Vec2(state.x[2 * i], state.x[2 * i + 1]));
  // Coloured by another field than det F (when the state has its values): its scale.
  FieldScale scale;
  FieldStats stats;
  const bool by_field = state.color_by != TriangleField::DetF && !state.triangles.empty() &&
                        state.field.size() == state.triangles.size();
  if (by_field) {
    stats = field_stats(state.color_by, state.field);
    scale = options.field_scale && options.field_scale->field == state.color_by
                ? *options.field_scale
                : auto_field_scale(state.color_by, stats);
  }
  add_plane_fills(v, L, cam, state);
  add_mesh_fills(v.shapes, p, state, options.color_range, by_field ? &scale : nullptr);
  ShapeRanges ranges;
  ranges.world_fills = v.shapes.size();
  add_strokes(v, L, cam, state, p, options.edges);
  if (options.ring_inverted) add_inverted_rings(v.shapes, p, state, L.scale);
  if (options.stress_glyphs) add_stress_glyphs(v, p, state, L);
  add_overlays(v.shapes, state, cam, L.scale);
  add_selected_outline(v.shapes, p, state, options.selected_triangle, L.scale);
  if (!options.title.empty()) add_title(v, L, options.title);
  if (!state.failure.empty())
    add_failure_mark(v, L, state.failure, options.title.empty() ? 0.0 : title_band_height(L));
  ranges.world_end = v.shapes.size();
  const DetFSummary det = summarize_det_f(state);
  ranges.panel_backdrop = options.panel ? draw_panel(v, L, state, det.lo, det.hi, det.inverted,
                                                     options, by_field ? &scale : nullptr, stats)
                                        : ranges.world_end;
  return ranges;
}

}  // namespace invfree::render
