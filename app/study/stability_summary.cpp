#include "app/study/stability_summary.h"

#include <algorithm>
#include <cmath>

#include "app/colormap.h"
#include "app/format_number.h"
#include "app/study/stability_palette.h"

namespace invfree {

namespace {

constexpr double kWidth = 1920, kHeight = 1080;

// The largest size <= `size` at which `text` fits `width`.
double fitted(const std::string& text, double size, double width) {
  const double w = text_width(text, size);
  return w <= width ? size : size * width / w;
}

}  // namespace

std::string summary_cell_text(const StabilityCell& c) {
  switch (cell_class(c.verdict)) {
    case CellClass::Ok:
      return std::isfinite(c.min_det_f) ? format_number(c.min_det_f, "%.2f") : "ok";
    case CellClass::InversionAllowed:
      return "inv. (allowed)";
    case CellClass::NotApplicable:
      return "n/a";
    case CellClass::Failed:
      break;
  }
  return verdict_name(c.verdict);
}

std::string stability_takeaway(const StabilityResult& r) {
  std::string s;
  std::string worst;
  int worst_failed = 0, worst_ran = 0;
  for (size_t m = 0; m < r.methods.size(); ++m) {
    int ok = 0, failed = 0, ran = 0;
    for (size_t k = 0; k < r.scenes.size(); ++k) {
      const CellClass c = cell_class(r.at(m, k).verdict);
      ran += c != CellClass::NotApplicable;
      ok += c == CellClass::Ok || c == CellClass::InversionAllowed;
      failed += c == CellClass::Failed;
    }
    if (r.methods[m] == "lecture")
      s = failed == 0
              ? "The lecture's method is ok on all " + std::to_string(ran) + " scenes it can start"
              : "The lecture's method fails on " + std::to_string(failed) + " of " +
                    std::to_string(ran) + " scenes";
    if (failed > worst_failed) {
      worst_failed = failed;
      worst_ran = ran;
      worst = r.methods[m];
    }
  }
  if (!worst.empty() && worst != "lecture")
    s += std::string(s.empty() ? "" : "; ") + worst + " fails on " + std::to_string(worst_failed) +
         " of " + std::to_string(worst_ran);
  if (s.empty()) s = "Every method is ok on every scene it can start";
  return s;
}

std::unique_ptr<Canvas> stability_summary(const StabilityResult& r, ChartFormat format) {
  auto canvas = std::make_unique<Canvas>(kWidth, kHeight, format);
  Canvas& img = *canvas;
  const double title_size = fitted(stability_takeaway(r), 52, kWidth - 80);
  img.text(stability_takeaway(r), kWidth / 2.0, 78, title_size, kSheetInk, Align::Center);
  const size_t rows = std::max<size_t>(r.methods.size(), 1),
               cols = std::max<size_t>(r.scenes.size(), 1);
  const double legend_h = 70, header_h = 190, top = 110 + header_h;
  double left = 0;
  const double name_size = std::min(40.0, (kHeight - top - legend_h) / rows * 0.45);
  for (const std::string& m : r.methods) left = std::max(left, text_width(m, name_size));
  left += 50;
  const double cw = (kWidth - left - 30) / cols, ch = (kHeight - top - legend_h) / rows;
  // Column headings, turned to read bottom to top, in up to two lines, so long scene
  // labels keep a readable size.
  for (size_t k = 0; k < r.scenes.size(); ++k) {
    const double size = std::min(28.0, cw * 0.32);
    std::vector<std::string> lines = wrap_text(r.scene_labels[k], size, header_h - 10);
    if (lines.size() > 2) {
      for (size_t i = 2; i < lines.size(); ++i) lines[1] += " " + lines[i];
      lines.resize(2);
    }
    for (size_t i = 0; i < lines.size(); ++i) {
      const double x =
          left + (k + 0.5) * cw + size * (0.35 + 1.15 * (i - 0.5 * (lines.size() - 1)));
      img.text(lines[i], x, top - 8, fitted(lines[i], size, header_h - 10), kSheetInk, Align::Left,
               true);
    }
  }
  const double cell_size = std::min(34.0, ch * 0.42);
  for (size_t m = 0; m < r.methods.size(); ++m) {
    const double y = top + m * ch;
    img.text(r.methods[m], 30, y + ch / 2.0 + name_size * 0.35, name_size, kSheetInk);
    for (size_t k = 0; k < r.scenes.size(); ++k) {
      const StabilityCell& c = r.at(m, k);
      const CellClass cls = cell_class(c.verdict);
      const Rgb fill = class_fill(cls, c.min_det_f);
      const double x = left + k * cw;
      img.fill_rect(x + 2, y + 2, x + cw - 2, y + ch - 2, fill);
      const std::string text = summary_cell_text(c);
      const auto lines = cls == CellClass::Ok ? std::vector<std::string>{text}
                                              : wrap_text(text, cell_size * 0.8, cw - 10);
      const double size = cls == CellClass::Ok ? fitted(text, cell_size, cw - 10) : cell_size * 0.8;
      const double y0 = y + ch / 2.0 - (lines.size() - 1) * size * 0.6 + size * 0.35;
      for (size_t i = 0; i < lines.size(); ++i)
        img.text(lines[i], x + cw / 2.0, y0 + i * size * 1.2, fitted(lines[i], size, cw - 8),
                 cls == CellClass::NotApplicable ? kSheetMuted : ink_on(fill), Align::Center);
    }
  }
  // The key, one line under the grid.
  const double ky = kHeight - 24, ks = 26;
  double kx = 30;
  auto key = [&](Rgb fill, const std::string& text) {
    img.fill_rect(kx, ky - ks * 0.8, kx + ks, ky + ks * 0.15, fill);
    img.stroke_rect(kx, ky - ks * 0.8, kx + ks, ky + ks * 0.15, 1.0, kSheetInk);
    img.text(text, kx + ks + 10, ky, ks, kSheetInk);
    kx += ks + 10 + text_width(text, ks) + 36;
  };
  key(det_f_color(0.3), "ok: its smallest det F over the run");
  key(class_fill(CellClass::Failed, NAN), "failed");
  key(class_fill(CellClass::InversionAllowed, NAN), "inverted, allowed by the model");
  key(class_fill(CellClass::NotApplicable, NAN), "n/a");
  img.text(std::string(r.quick ? "quick run; " : "") + "invfree stability", kWidth - 30, ky, 20,
           kSheetMuted, Align::Right);
  return canvas;
}

}  // namespace invfree
