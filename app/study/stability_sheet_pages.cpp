#include "app/study/stability_sheet_pages.h"

#include <algorithm>
#include <cmath>

#include "app/format_number.h"
#include "app/study/contact_sheet.h"
#include "app/study/frame_thumbnail.h"
#include "app/study/stability_palette.h"

namespace invfree {

namespace {

constexpr double kMargin = 40, kGap = 24;
constexpr double kGridTop = 130, kKeyHeight = 112;
constexpr double kKeyScale = 1.25;

// The largest size <= `size` at which `text` fits `width`.
double fitted(const std::string& text, double size, double width) {
  const double w = text_width(text, size);
  return w <= width ? size : size * width / w;
}

struct MethodRecord {
  int failed = 0, allowed = 0, ran = 0;
};

MethodRecord record_of(const StabilityResult& r, size_t m) {
  MethodRecord rec;
  for (size_t k = 0; k < r.scenes.size(); ++k) {
    const CellClass c = cell_class(r.at(m, k).verdict);
    rec.ran += c != CellClass::NotApplicable;
    rec.failed += c == CellClass::Failed;
    rec.allowed += c == CellClass::InversionAllowed;
  }
  return rec;
}

// "symplectic-euler fails on 14 of 14 scenes; arap inverts on 9 of 15, as its model allows"
std::string page_title(const StabilityResult& r, const std::vector<const StabilityCell*>& runs) {
  std::string s;
  for (size_t m = 0; m < r.methods.size(); ++m) {
    if (std::none_of(runs.begin(), runs.end(),
                     [&](const StabilityCell* c) { return c->method == r.methods[m]; }))
      continue;
    const MethodRecord rec = record_of(r, m);
    const std::string of = " of " + std::to_string(rec.ran);
    std::string part = r.methods[m];
    if (rec.failed > 0) part += " fails on " + std::to_string(rec.failed) + of;
    if (rec.allowed > 0)
      part += (rec.failed > 0 ? " and inverts on " : " inverts on ") + std::to_string(rec.allowed) +
              (rec.failed > 0 ? "" : of) + ", as its model allows";
    s += (s.empty() ? "" : "; ") + part;
  }
  return s;
}

std::string scene_label(const StabilityResult& r, const std::string& scene) {
  for (size_t k = 0; k < r.scenes.size(); ++k)
    if (r.scenes[k] == scene) return r.scene_labels[k];
  return scene;
}

}  // namespace

std::vector<const StabilityCell*> sheet_runs(const StabilityResult& r) {
  std::vector<const StabilityCell*> runs;
  for (const StabilityCell& c : r.cells) {
    const CellClass cls = cell_class(c.verdict);
    if (cls == CellClass::Failed || cls == CellClass::InversionAllowed) runs.push_back(&c);
  }
  return runs;
}

SheetGrid sheet_grid(size_t runs) {
  if (runs <= 1) return {1, 1};
  if (runs <= 2) return {2, 1};
  if (runs <= 3) return {3, 1};
  if (runs <= 4) return {2, 2};
  if (runs <= 6) return {3, 2};
  return {4, 2};
}

std::string sheet_verdict_text(const StabilityCell& c) {
  const std::string when = "t = " + format_number(c.fail_step * c.h, "%.3g") + " s";
  if (cell_class(c.verdict) == CellClass::InversionAllowed)
    return "inverted at " + when + ", allowed";
  return std::string(verdict_name(c.verdict)) + " at " + when;
}

std::vector<SheetPage> stability_sheet_pages(const StabilityResult& r, ChartFormat format) {
  const std::vector<const StabilityCell*> runs = sheet_runs(r);
  int ok = 0, na = 0;
  for (const StabilityCell& c : r.cells) {
    ok += cell_class(c.verdict) == CellClass::Ok;
    na += cell_class(c.verdict) == CellClass::NotApplicable;
  }
  const size_t pages =
      std::max<size_t>(1, (runs.size() + kSheetRunsPerPage - 1) / kSheetRunsPerPage);
  // One grid for every page, so a run looks the same size on each.
  const SheetGrid grid = sheet_grid(std::min(runs.size(), kSheetRunsPerPage));
  const double cell_w = (kSheetPageWidth - 2 * kMargin - (grid.cols - 1) * kGap) / grid.cols;
  const double cell_h =
      (kSheetPageHeight - kGridTop - kKeyHeight - (grid.rows - 1) * kGap) / grid.rows;
  const double text = std::clamp(cell_w / 16.0, 26.0, 40.0);
  const double caption_h = 3 * text * 1.22 + 8;
  std::vector<SheetPage> out;
  for (size_t p = 0; p < pages; ++p) {
    SheetPage page;
    page.canvas = std::make_unique<Canvas>(kSheetPageWidth, kSheetPageHeight, format);
    Canvas& img = *page.canvas;
    const size_t begin = p * kSheetRunsPerPage,
                 end = std::min(runs.size(), begin + kSheetRunsPerPage);
    const std::vector<const StabilityCell*> here(runs.begin() + begin, runs.begin() + end);
    page.title =
        here.empty() ? "Every method is ok on every scene it can start" : page_title(r, here);
    img.text(page.title, kSheetPageWidth / 2.0, 64,
             fitted(page.title, 46, kSheetPageWidth - 2 * kMargin), kSheetInk, Align::Center);
    std::string sub =
        "The last frame before each failure (red) or the final frame of an inversion the model "
        "allows (blue), coloured by det F";
    if (pages > 1)
      sub += "  \u00b7  page " + std::to_string(p + 1) + " of " + std::to_string(pages);
    img.text(sub, kSheetPageWidth / 2.0, 104, fitted(sub, 26, kSheetPageWidth - 2 * kMargin),
             kSheetMuted, Align::Center);
    for (size_t i = 0; i < here.size(); ++i) {
      const StabilityCell& c = *here[i];
      const int col = static_cast<int>(i) % grid.cols, row = static_cast<int>(i) / grid.cols;
      const double x = kMargin + col * (cell_w + kGap), y = kGridTop + row * (cell_h + kGap);
      const double thumb_h = cell_h - caption_h;
      draw_frame_fitted(img, c.frame, x, y, cell_w, thumb_h);
      const Rgb ink = class_ink(cell_class(c.verdict));
      img.stroke_rect(x + 2, y + 2, x + cell_w - 2, y + thumb_h - 2, 4.0, ink);
      page.thumbs.push_back({&c, x, y, x + cell_w, y + thumb_h});
      const std::string lines[] = {c.method, scene_label(r, c.scene), sheet_verdict_text(c)};
      const Rgb colors[] = {kSheetInk, kSheetInk, ink};
      const double sizes[] = {text, text * 0.92, text * 0.92};
      double ty = y + thumb_h + 6;
      for (int l = 0; l < 3; ++l) {
        ty += sizes[l] * 1.18;
        img.text(lines[l], x + cell_w / 2.0, ty - sizes[l] * 0.22,
                 fitted(lines[l], sizes[l], cell_w - 8), colors[l], Align::Center);
      }
    }
    if (here.empty())
      img.text("no run failed or inverted", kSheetPageWidth / 2.0, kSheetPageHeight / 2.0, 40,
               kSheetMuted, Align::Center);
    // The key, and beside it what is left out and where to find it.
    draw_sheet_key(img, kMargin + 90, kSheetPageHeight - kKeyHeight + 40, kKeyScale, false);
    const std::string left_out[] = {"Not shown: " + std::to_string(ok) + " ok run" +
                                        (ok == 1 ? "" : "s") + ", " + std::to_string(na) + " n/a",
                                    "--slides: their smallest det F; --full-sheet: every run"};
    for (int l = 0; l < 2; ++l)
      img.text(left_out[l], kSheetPageWidth - kMargin, kSheetPageHeight - 62 + 32 * l,
               fitted(left_out[l], 24, 640), kSheetMuted, Align::Right);
    out.push_back(std::move(page));
  }
  return out;
}

}  // namespace invfree
