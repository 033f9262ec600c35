// The stability contact sheet a class can read (`invfree stability`: stability-sheet-1.png,
// -2, ...): 16:9 pages (1920x1080) that show, large, only the runs that matter: every run
// that failed (framed red) and every inversion its model allows (framed blue), in the
// table's order (by method, then scene), at most kSheetRunsPerPage a page. Each is a
// thumbnail framed on its bodies (frame_thumbnail.h) with its method, its scene and its
// verdict with when it happened in large type. The title is the page's takeaway (how often
// each method on it fails), the subtitle what is left out: the ok runs (the summary slide,
// stability_summary.h, gives their smallest det F) and the n/a ones; the full sheet
// (contact_sheet.h, --full-sheet) has every run. The det F key closes each page.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/plot/canvas.h"
#include "app/study/stability.h"

namespace invfree {

constexpr size_t kSheetRunsPerPage = 8;
constexpr double kSheetPageWidth = 1920, kSheetPageHeight = 1080;

// The runs the pages show, in order: failed or inverted as the model allows.
std::vector<const StabilityCell*> sheet_runs(const StabilityResult& result);

// Columns and rows of a page's grid for `runs` thumbnails (at most kSheetRunsPerPage):
// the fewer, the larger.
struct SheetGrid {
  int cols = 1, rows = 1;
};
SheetGrid sheet_grid(size_t runs);

// Where a run's thumbnail (the picture, without its caption) lies on its page.
struct SheetThumb {
  const StabilityCell* cell = nullptr;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct SheetPage {
  std::unique_ptr<Canvas> canvas;
  std::vector<SheetThumb> thumbs;
  std::string title;
};

// What a thumbnail says under it: "penetrated at t = 0.36 s", "inverted at t = 0.05 s,
// allowed" (its blue frame and colour say by whom: the model).
std::string sheet_verdict_text(const StabilityCell& cell);

// At least one page (with no run to show, one that says so).
std::vector<SheetPage> stability_sheet_pages(const StabilityResult& result, ChartFormat format);

}  // namespace invfree
