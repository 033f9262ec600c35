#include "app/study/frame_thumbnail.h"

#include <algorithm>
#include <cmath>

#include "app/colormap.h"
#include "app/study/stability_palette.h"

namespace invfree {

namespace {

constexpr Rgb kPlane{0.30f, 0.30f, 0.32f};
constexpr Rgb kPlaneFill{0.93f, 0.93f, 0.94f};
constexpr Rgb kBorder{0.75f, 0.75f, 0.77f};
// Mesh edges are drawn only where a triangle's edge is at least this long on screen.
constexpr double kMinEdgePx = 6.0;

// The world window shown: x from `left`, y from `bottom` up, `scale` pixels per metre.
struct Window {
  double left = 0.0, bottom = 0.0, scale = 1.0;
};

void draw_in_window(Canvas& cell, const Frame& f, double x0, double y0, double w, double h,
                    const Window& win) {
  // The picture is clipped, so anything far outside (a blown-up run) stays in it.
  cell.push();
  cell.translate(x0, y0);
  cell.clip(0, 0, w, h);
  cell.fill_rect(0, 0, w, h, kSheetWhite);
  auto px = [&](double x, double y) {
    return Point2{(x - win.left) * win.scale, h - (y - win.bottom) * win.scale};
  };
  if (f.has_ground) {
    const double gy = px(0.0, f.ground_y).y;
    cell.fill_rect(0, gy, w, h, kPlaneFill);
    cell.line({0, gy}, {w, gy}, 1.5, kPlane);
  }
  if (f.has_ceiling) {
    const double cy = px(0.0, f.ceiling_y).y;
    cell.fill_rect(0, 0, w, cy, kPlaneFill);
    cell.line({0, cy}, {w, cy}, 1.5, kPlane);
  }
  std::vector<Point2> nodes(f.x.size() / 2);
  for (size_t i = 0; i < nodes.size(); ++i) nodes[i] = px(f.x[2 * i], f.x[2 * i + 1]);
  // Inverted triangles are drawn last, so one folded under its neighbours still shows.
  std::vector<std::array<int, 3>> tris;
  std::vector<Rgb> colors;
  for (int pass = 0; pass < 2; ++pass)
    for (size_t t = 0; t < f.det_f.size(); ++t)
      if ((f.det_f[t] > 0.0) == (pass == 0)) {
        tris.push_back(f.mesh.triangles[t]);
        colors.push_back(det_f_color(f.det_f[t]));
      }
  cell.triangles(nodes, tris, colors);
  // Edges only where a cell of the mesh is large on screen: at the 64x64 fold's few pixels
  // per triangle, edges 0.6 px wide covered the colour and the body rendered black.
  double edge_px = 0.0;
  for (const auto& t : tris)
    edge_px += std::hypot(nodes[t[1]].x - nodes[t[0]].x, nodes[t[1]].y - nodes[t[0]].y);
  edge_px /= std::max<size_t>(tris.size(), 1);
  if (edge_px >= kMinEdgePx)
    for (const auto& t : tris)
      cell.polyline({nodes[t[0]], nodes[t[1]], nodes[t[2]], nodes[t[0]]}, 0.6, kSheetInk,
                    std::min(0.45, 0.45 * edge_px / (2.0 * kMinEdgePx)));
  // A triangle that has just gone through det F = 0 is a sliver too thin to see: mark it,
  // with a ring that grows with the picture.
  const double ring = std::max(4.5, std::min(w, h) / 40.0);
  for (size_t t = 0; t < f.det_f.size(); ++t)
    if (!(f.det_f[t] > 0.0)) {
      const auto& tri = f.mesh.triangles[t];
      const Point2 c{(nodes[tri[0]].x + nodes[tri[1]].x + nodes[tri[2]].x) / 3.0,
                     (nodes[tri[0]].y + nodes[tri[1]].y + nodes[tri[2]].y) / 3.0};
      cell.ring(c, ring, ring * 0.65, kSheetInk);
      cell.ring(c, ring, ring * 0.4, kInvertedColor);
    }
  cell.stroke_rect(0.5, 0.5, w - 0.5, h - 0.5, 1.0, kBorder);
  cell.pop();
}

}  // namespace

void draw_frame(Canvas& cell, const Frame& f, double x0, double y0, double size) {
  double span = 1.7 * f.side, cx = 0.0;
  const double ground = f.has_ground ? f.ground_y : -f.side;
  const double bottom = ground - 0.05 * f.side;
  if (f.mesh.body_begin.size() > 1 && f.x.size() >= 2) {
    // Several bodies go their own ways (the stack's top square slides off): frame them all,
    // from the ground up, centred on them.
    double x_lo = f.x[0], x_hi = f.x[0], y_hi = f.x[1];
    for (Eigen::Index i = 0; i + 1 < f.x.size(); i += 2) {
      x_lo = std::min(x_lo, f.x[i]);
      x_hi = std::max(x_hi, f.x[i]);
      y_hi = std::max(y_hi, f.x[i + 1]);
    }
    if (std::isfinite(x_lo) && std::isfinite(x_hi) && std::isfinite(y_hi)) {
      span = std::max({span, 1.15 * (x_hi - x_lo), 1.15 * (y_hi - bottom)});
      cx = 0.5 * (x_lo + x_hi);
    }
  }
  draw_in_window(cell, f, x0, y0, size, size, {cx - 0.5 * span, bottom, size / span});
}

void draw_frame_fitted(Canvas& cell, const Frame& f, double x0, double y0, double w, double h) {
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  for (Eigen::Index i = 0; i + 1 < f.x.size(); i += 2)
    if (std::isfinite(f.x[i]) && std::isfinite(f.x[i + 1])) {
      x_lo = std::min(x_lo, f.x[i]);
      x_hi = std::max(x_hi, f.x[i]);
      y_lo = std::min(y_lo, f.x[i + 1]);
      y_hi = std::max(y_hi, f.x[i + 1]);
    }
  if (!(x_lo <= x_hi)) {  // no finite node: the square window around the ground
    x_lo = -0.85 * f.side;
    x_hi = 0.85 * f.side;
    y_lo = y_hi = f.has_ground ? f.ground_y : 0.0;
  }
  // The ground is always in view (a node through it is the failure to see), a ceiling
  // when it is close enough above the bodies to matter.
  if (f.has_ground) y_lo = std::min(y_lo, f.ground_y - 0.04 * f.side);
  if (f.has_ceiling && f.ceiling_y - y_hi < 0.5 * f.side)
    y_hi = std::max(y_hi, f.ceiling_y + 0.04 * f.side);
  // A margin, and never closer than a quarter of the side (a strip stays a strip).
  const double margin = 0.08 * std::max({x_hi - x_lo, y_hi - y_lo, 0.25 * f.side});
  x_lo -= margin;
  x_hi += margin;
  y_hi += margin;
  if (!f.has_ground) y_lo -= margin;
  const double span_x = std::max(x_hi - x_lo, 0.25 * f.side),
               span_y = std::max(y_hi - y_lo, 0.25 * f.side);
  const double scale = std::min(w / span_x, h / span_y);
  // Centred horizontally; vertically the ground stays at the bottom margin.
  const double left = 0.5 * (x_lo + x_hi) - 0.5 * w / scale;
  const double bottom = f.has_ground ? y_lo : 0.5 * (y_lo + y_hi) - 0.5 * h / scale;
  draw_in_window(cell, f, x0, y0, w, h, {left, bottom, scale});
}

}  // namespace invfree
