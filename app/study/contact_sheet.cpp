#include "app/study/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/colormap.h"
#include "app/format_number.h"
#include "app/plot/canvas.h"
#include "app/study/frame_thumbnail.h"
#include "app/study/stability_palette.h"

namespace invfree {

Rgb cell_class_color(CellClass c) {
  return class_ink(c);
}

std::string cell_caption(const StabilityCell& c) {
  switch (cell_class(c.verdict)) {
    case CellClass::InversionAllowed:
      return "inverted, allowed";
    default:
      return verdict_name(c.verdict);
  }
}

namespace {

std::string min_det_f_text(const StabilityCell& c) {
  return "min det F " + format_number(c.min_det_f, "%.2g");
}

// One run's cell at (x, y): its frame (or "n/a" and why), the verdict and when it ended.
void draw_cell(Canvas& img, const StabilityCell& c, int x, int y, int cell) {
  if (c.verdict == Verdict::NotApplicable) {
    img.fill_rect(x, y, x + cell, y + cell, {0.96f, 0.96f, 0.96f});
    img.text("n/a", x + cell / 2.0, y + cell / 2.0, 22, kSheetMuted, Align::Center);
    const auto why = wrap_text(
        c.message.find("inverted") != std::string::npos ? "cannot start inverted" : "cannot start",
        13, cell - 10);
    for (size_t i = 0; i < why.size(); ++i)
      img.text(why[i], x + cell / 2.0, y + cell / 2.0 + 22 + 16.0 * i, 13, kSheetMuted,
               Align::Center);
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
      img.stroke_rect(tx, y + cell + 24, tx + sw, y + cell + 24 + sw, 0.8, kSheetInk);
      img.text(min_det_f_text(c), tx + sw + 4, y + cell + 33, 12, kSheetMuted);
    }
    sub = "t = " + format_number(c.frame.time, "%.2f") + " s";
  } else if (cls != CellClass::NotApplicable) {
    sub = failure_time(c);
  }
  const double sub_top = cls == CellClass::Ok && std::isfinite(c.min_det_f) ? 14.0 : 0.0;
  const auto sub_lines = wrap_text(sub, 12, cell - 4);
  for (size_t i = 0; i < sub_lines.size(); ++i)
    img.text(sub_lines[i], x + cell / 2.0, y + cell + 33 + sub_top + 14.0 * i, 12, kSheetMuted,
             Align::Center);
}

}  // namespace

void draw_sheet_key(Canvas& img, double bx, double by, double k, bool frames) {
  const double bw = 520 * k, bh = 18 * k;
  img.text("det F", bx - 12 * k, by + 14 * k, 16 * k, kSheetInk, Align::Right);
  const int steps = static_cast<int>(bw);
  for (int i = 0; i < steps; ++i) {
    const double t = -1.0 + 2.0 * (i + 0.5) / steps;
    img.fill_rect(bx + i * bw / steps, by, bx + (i + 1) * bw / steps, by + bh, diverging_color(t));
  }
  img.stroke_rect(bx, by, bx + bw, by + bh, 1.0, kSheetInk);
  const double ticks[] = {1.0 / kDetFRange, 0.5, 1.0, 2.0, kDetFRange};
  for (double d : ticks) {
    const double xpos = bx + (det_f_scale_position(d) + 1.0) / 2.0 * bw;
    img.line({xpos, by + bh}, {xpos, by + bh + 5.0 * k}, 1.0, kSheetInk);
    char label[32];
    std::snprintf(label, sizeof label,
                  d == 1.0 / kDetFRange ? "\u2264 %.3g"
                  : d == kDetFRange     ? "\u2265 %.3g"
                                        : "%.3g",
                  d);
    img.text(label, xpos, by + bh + 21 * k, 14 * k, kSheetInk, Align::Center);
  }
  const double sx = bx + bw + 40 * k;
  img.fill_rect(sx, by, sx + 40 * k, by + bh, kInvertedColor);
  img.stroke_rect(sx, by, sx + 40 * k, by + bh, 1.0, kSheetInk);
  img.text("det F \u2264 0 (inverted; ringed)", sx + 50 * k, by + 14 * k, 15 * k, kSheetInk);
  if (frames) {
    img.text("red frame: failed;", sx, by + 44 * k, 15 * k, kSheetFailed);
    img.text("blue frame: inverted, allowed by the model (linear, ARAP, stable neo-Hookean)",
             sx + text_width("red frame: failed; ", 15 * k), by + 44 * k, 15 * k, kSheetAllowed);
  }
  img.text("compressed", bx, by - 6 * k, 13 * k, kSheetMuted);
  img.text("stretched", bx + bw, by - 6 * k, 13 * k, kSheetMuted, Align::Right);
}

std::unique_ptr<Canvas> contact_sheet(const StabilityResult& r, ChartFormat format) {
  const int cell = 150, gap = 10, caption = 54;
  const int left = 230, top = 130, bar_h = 90;
  const int cols = static_cast<int>(r.scenes.size()), rows = static_cast<int>(r.methods.size());
  const std::string title =
      "Where methods fail: the final frame of each run, or the last frame before it failed, "
      "coloured by det F";
  const std::string subtitle =
      std::string(r.quick ? "A quick run: each scene until the ceiling stops. " : "") +
      "rows: methods; columns: stress scenes (assets/scenes/stress-*.toml, then the "
      "course's squash); symplectic Euler takes 20 steps per scene step";
  // As wide as the cells, or as the title and the key where a few columns are run
  // (--scenes).
  const double key_width = 520 + 40 +
                           text_width(
                               "red frame: failed; blue frame: inverted, allowed by the model "
                               "(linear, ARAP, stable neo-Hookean)",
                               15);
  const int width = static_cast<int>(
      std::ceil(std::max({left + cols * (cell + gap) + 20.0, 40 + text_width(title, 24),
                          40 + text_width(subtitle, 16), left + key_width + 20})));
  const int height = top + rows * (cell + caption + gap) + bar_h;
  auto canvas = std::make_unique<Canvas>(width, height, format);
  Canvas& img = *canvas;
  img.text(title, 20, 36, 24, kSheetInk);
  img.text(subtitle, 20, 64, 16, kSheetMuted);
  for (int k = 0; k < cols; ++k) {
    const double cx = left + k * (cell + gap) + cell / 2.0;
    const auto lines = wrap_text(r.scene_labels[k], 16, cell);
    for (size_t i = 0; i < lines.size(); ++i)
      img.text(lines[i], cx, top - 30 - 20.0 * (lines.size() - 1 - i), 16, kSheetInk,
               Align::Center);
    img.text(r.scenes[k], cx, top - 10, 11, kSheetMuted, Align::Center);
  }
  for (int m = 0; m < rows; ++m) {
    const int y = top + m * (cell + caption + gap);
    const auto lines = wrap_text(r.method_labels[m], 15, left - 30);
    img.text(r.methods[m], 20, y + 40, 17, kSheetInk);
    for (size_t i = 0; i < lines.size(); ++i)
      img.text(lines[i], 20, y + 64 + 19.0 * i, 14, kSheetMuted);
    for (int k = 0; k < cols; ++k) draw_cell(img, r.at(m, k), left + k * (cell + gap), y, cell);
  }
  draw_sheet_key(img, left, height - bar_h + 30, 1.0, true);
  return canvas;
}

}  // namespace invfree
