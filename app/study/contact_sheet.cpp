#include "app/study/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/colormap.h"
#include "app/format_number.h"
#include "app/plot/canvas.h"

namespace invfree {

namespace {

constexpr Rgb kWhite{1.0f, 1.0f, 1.0f};
constexpr Rgb kInk{0.10f, 0.10f, 0.12f};
constexpr Rgb kMuted{0.45f, 0.45f, 0.48f};
constexpr Rgb kFail{0.78f, 0.08f, 0.10f};
constexpr Rgb kPlane{0.30f, 0.30f, 0.32f};
constexpr Rgb kPlaneFill{0.93f, 0.93f, 0.94f};
// An inversion the model allows: neutral slate blue, neither ok's ink nor a failure's red.
constexpr Rgb kAllowed{0.25f, 0.36f, 0.62f};
// Mesh edges are drawn only where a triangle's edge is at least this long on screen.
constexpr double kMinEdgePx = 6.0;

}  // namespace

Rgb cell_class_color(CellClass c) {
  switch (c) {
    case CellClass::Ok:
      return kInk;
    case CellClass::Failed:
      return kFail;
    case CellClass::InversionAllowed:
      return kAllowed;
    case CellClass::NotApplicable:
      return kMuted;
  }
  return kInk;
}

std::string cell_caption(const StabilityCell& c) {
  switch (cell_class(c.verdict)) {
    case CellClass::InversionAllowed:
      return "inverted, allowed";
    default:
      return verdict_name(c.verdict);
  }
}

namespace {}  // namespace

void draw_frame(Canvas& cell, const Frame& f, double x0, double y0, double size) {
  // The cell is clipped, so anything far outside (a blown-up run) stays in it.
  cell.push();
  cell.translate(x0, y0);
  cell.clip(0, 0, size, size);
  cell.fill_rect(0, 0, size, size, kWhite);
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
  const double scale = size / span;
  auto px = [&](double x, double y) {
    return Point2{(x - cx + 0.5 * span) * scale, size - (y - bottom) * scale};
  };
  if (f.has_ground) {
    const double gy = px(0.0, f.ground_y).y;
    cell.fill_rect(0, gy, size, size, kPlaneFill);
    cell.line({0, gy}, {size, gy}, 1.5, kPlane);
  }
  if (f.has_ceiling) {
    const double cy = px(0.0, f.ceiling_y).y;
    cell.fill_rect(0, 0, size, cy, kPlaneFill);
    cell.line({0, cy}, {size, cy}, 1.5, kPlane);
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
      cell.polyline({nodes[t[0]], nodes[t[1]], nodes[t[2]], nodes[t[0]]}, 0.6, kInk,
                    std::min(0.45, 0.45 * edge_px / (2.0 * kMinEdgePx)));
  // A triangle that has just gone through det F = 0 is a sliver too thin to see: mark it.
  for (size_t t = 0; t < f.det_f.size(); ++t)
    if (!(f.det_f[t] > 0.0)) {
      const auto& tri = f.mesh.triangles[t];
      const Point2 c{(nodes[tri[0]].x + nodes[tri[1]].x + nodes[tri[2]].x) / 3.0,
                     (nodes[tri[0]].y + nodes[tri[1]].y + nodes[tri[2]].y) / 3.0};
      cell.ring(c, 4.5, 3.0, kInk);
      cell.ring(c, 4.5, 1.8, kInvertedColor);
    }
  cell.stroke_rect(0.5, 0.5, size - 0.5, size - 0.5, 1.0, {0.75f, 0.75f, 0.77f});
  cell.pop();
}

namespace {

std::string min_det_f_text(const StabilityCell& c) {
  return "min det F " + format_number(c.min_det_f, "%.2g");
}

// One run's cell at (x, y): its frame (or "n/a" and why), the verdict and when it ended.
void draw_cell(Canvas& img, const StabilityCell& c, int x, int y, int cell) {
  if (c.verdict == Verdict::NotApplicable) {
    img.fill_rect(x, y, x + cell, y + cell, {0.96f, 0.96f, 0.96f});
    img.text("n/a", x + cell / 2.0, y + cell / 2.0, 22, kMuted, Align::Center);
    const auto why = wrap_text(
        c.message.find("inverted") != std::string::npos ? "cannot start inverted" : "cannot start",
        13, cell - 10);
    for (size_t i = 0; i < why.size(); ++i)
      img.text(why[i], x + cell / 2.0, y + cell / 2.0 + 22 + 16.0 * i, 13, kMuted, Align::Center);
  } else {
    draw_frame(img, c.frame, x, y, cell);
  }
  const CellClass cls = cell_class(c.verdict);
  // A failure is framed in red, an allowed inversion in the neutral colour.
  if (cls == CellClass::Failed || cls == CellClass::InversionAllowed)
    img.stroke_rect(x + 1.5, y + 1.5, x + cell - 1.5, y + cell - 1.5, 3.0, cell_class_color(cls));
  img.text(cell_caption(c), x + cell / 2.0, y + cell + 17, 16, cell_class_color(cls),
           Align::Center);
  // An ok run says how close it came to inverting (the smallest det F over the run, with
  // its colour), so two ok cells read differently.
  std::string sub;
  if (cls == CellClass::Ok) {
    if (std::isfinite(c.min_det_f)) {
      const double sw = 11.0;
      const double tx = x + cell / 2.0 - (text_width(min_det_f_text(c), 12) + sw + 4) / 2.0;
      img.fill_rect(tx, y + cell + 24, tx + sw, y + cell + 24 + sw, det_f_color(c.min_det_f));
      img.stroke_rect(tx, y + cell + 24, tx + sw, y + cell + 24 + sw, 0.8, kInk);
      img.text(min_det_f_text(c), tx + sw + 4, y + cell + 33, 12, kMuted);
    }
    sub = "t = " + format_number(c.frame.time, "%.2f") + " s";
  } else if (cls != CellClass::NotApplicable) {
    sub = failure_time(c);
  }
  const double sub_top = cls == CellClass::Ok && std::isfinite(c.min_det_f) ? 14.0 : 0.0;
  const auto sub_lines = wrap_text(sub, 12, cell - 4);
  for (size_t i = 0; i < sub_lines.size(); ++i)
    img.text(sub_lines[i], x + cell / 2.0, y + cell + 33 + sub_top + 14.0 * i, 12, kMuted,
             Align::Center);
}

// The det F colour bar with its ticks at (bx, by), and the det F <= 0 swatch beside it.
void draw_color_bar(Canvas& img, int bx, int by) {
  const int bw = 520, bh = 18;
  img.text("det F", 20, by + 14, 16, kInk);
  for (int i = 0; i < bw; ++i) {
    const double t = -1.0 + 2.0 * (i + 0.5) / bw;
    img.fill_rect(bx + i, by, bx + i + 1, by + bh, diverging_color(t));
  }
  img.stroke_rect(bx, by, bx + bw, by + bh, 1.0, kInk);
  const double ticks[] = {1.0 / kDetFRange, 0.5, 1.0, 2.0, kDetFRange};
  for (double d : ticks) {
    const double xpos = bx + (det_f_scale_position(d) + 1.0) / 2.0 * bw;
    img.line({xpos, double(by + bh)}, {xpos, by + bh + 5.0}, 1.0, kInk);
    char label[32];
    std::snprintf(label, sizeof label,
                  d == 1.0 / kDetFRange ? "\u2264 %.3g"
                  : d == kDetFRange     ? "\u2265 %.3g"
                                        : "%.3g",
                  d);
    img.text(label, xpos, by + bh + 21, 14, kInk, Align::Center);
  }
  img.fill_rect(bx + bw + 40, by, bx + bw + 80, by + bh, kInvertedColor);
  img.stroke_rect(bx + bw + 40, by, bx + bw + 80, by + bh, 1.0, kInk);
  img.text("det F \u2264 0 (inverted; ringed)", bx + bw + 90, by + 14, 15, kInk);
  img.text("red frame: failed;", bx + bw + 40, by + 44, 15, kFail);
  img.text("blue frame: inverted, allowed by the model (linear, ARAP, stable neo-Hookean)",
           bx + bw + 40 + text_width("red frame: failed; ", 15), by + 44, 15, kAllowed);
  img.text("compressed", bx, by - 6, 13, kMuted);
  img.text("stretched", bx + bw, by - 6, 13, kMuted, Align::Right);
}

}  // namespace

std::unique_ptr<Canvas> contact_sheet(const StabilityResult& r, ChartFormat format) {
  const int cell = 150, gap = 10, caption = 54;
  const int left = 230, top = 130, bar_h = 90;
  const int cols = static_cast<int>(r.scenes.size()), rows = static_cast<int>(r.methods.size());
  const int width = left + cols * (cell + gap) + 20;
  const int height = top + rows * (cell + caption + gap) + bar_h;
  auto canvas = std::make_unique<Canvas>(width, height, format);
  Canvas& img = *canvas;
  img.text(
      "Where methods fail: the final frame of each run, or the last frame before it failed, "
      "coloured by det F",
      20, 36, 24, kInk);
  img.text(std::string(r.quick ? "A quick run: each scene until the ceiling stops. " : "") +
               "rows: methods; columns: stress scenes (assets/scenes/stress-*.toml, then the "
               "course's squash); symplectic Euler takes 20 steps per scene step",
           20, 64, 16, kMuted);
  for (int k = 0; k < cols; ++k) {
    const double cx = left + k * (cell + gap) + cell / 2.0;
    const auto lines = wrap_text(r.scene_labels[k], 16, cell);
    for (size_t i = 0; i < lines.size(); ++i)
      img.text(lines[i], cx, top - 30 - 20.0 * (lines.size() - 1 - i), 16, kInk, Align::Center);
    img.text(r.scenes[k], cx, top - 10, 11, kMuted, Align::Center);
  }
  for (int m = 0; m < rows; ++m) {
    const int y = top + m * (cell + caption + gap);
    const auto lines = wrap_text(r.method_labels[m], 15, left - 30);
    img.text(r.methods[m], 20, y + 40, 17, kInk);
    for (size_t i = 0; i < lines.size(); ++i) img.text(lines[i], 20, y + 64 + 19.0 * i, 14, kMuted);
    for (int k = 0; k < cols; ++k) draw_cell(img, r.at(m, k), left + k * (cell + gap), y, cell);
  }
  draw_color_bar(img, left, height - bar_h + 30);
  return canvas;
}

}  // namespace invfree
