#include "app/study/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/colormap.h"
#include "app/plot/canvas.h"

namespace invfree {

namespace {

constexpr Rgb kWhite{1.0f, 1.0f, 1.0f};
constexpr Rgb kInk{0.10f, 0.10f, 0.12f};
constexpr Rgb kMuted{0.45f, 0.45f, 0.48f};
constexpr Rgb kFail{0.78f, 0.08f, 0.10f};
constexpr Rgb kPlane{0.30f, 0.30f, 0.32f};
constexpr Rgb kPlaneFill{0.93f, 0.93f, 0.94f};

}  // namespace

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
  for (const auto& t : tris)
    cell.polyline({nodes[t[0]], nodes[t[1]], nodes[t[2]], nodes[t[0]]}, 0.6, kInk, 0.45);
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
  const bool ok = c.verdict == Verdict::Ok;
  const std::string verdict = verdict_name(c.verdict);
  img.text(verdict, x + cell / 2.0, y + cell + 17, 16,
           ok ? kInk : (c.verdict == Verdict::NotApplicable ? kMuted : kFail), Align::Center);
  char sub[64];
  if (c.verdict == Verdict::NotApplicable)
    sub[0] = 0;
  else if (ok)
    std::snprintf(sub, sizeof sub, "t = %.2f s", c.frame.time);
  else
    std::snprintf(sub, sizeof sub, "%s", failure_time(c).c_str());
  const auto sub_lines = wrap_text(sub, 12, cell - 4);
  for (size_t i = 0; i < sub_lines.size(); ++i)
    img.text(sub_lines[i], x + cell / 2.0, y + cell + 33 + 14.0 * i, 12, kMuted, Align::Center);
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
