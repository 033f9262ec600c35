// Slide-ready charts (issue 32 item 5), checked by their data: the study's slides are one
// 16:9 chart each with large type, the methods that ran and a takeaway title computed from
// the points; a study whose errors do not fall with h draws no Pareto front and says so;
// the stability summary and the contact sheet tell an ok run from another (its smallest
// det F), an allowed inversion from a failure, and a 64x64 mesh shows its colour, not its
// edges; the sheet's pages (the one a class sees) are 16:9 with large thumbnails of every
// run that failed or inverted as allowed and no other, and the sheet's red is the slide's.
#include <gtest/gtest.h>
#include <stb/stb_image.h>  // its implementation is in chart_test.cpp

#include <algorithm>
#include <cmath>

#include "app/plot/chart.h"
#include "app/study/contact_sheet.h"
#include "app/study/stability_sheet_pages.h"
#include "app/study/stability_summary.h"
#include "app/study/study_chart.h"
#include "app/study/study_slides.h"
#include "scene/mesh.h"

namespace invfree {
namespace {

bool has_text(const Canvas& canvas, const std::string& text) {
  return std::any_of(canvas.texts().begin(), canvas.texts().end(),
                     [&](const TextItem& t) { return t.text.find(text) != std::string::npos; });
}

// Three methods of one model and one failing everywhere: lecture reaches 2% at 1 s/s,
// full-eigen-clamp the same 2% at 5 s/s, no-projection only 4% (at 0.3 s/s).
StudyResult three_methods() {
  StudyResult r;
  r.scene.name = "test";
  r.scene.h = 0.01;
  r.scene.tol = 0.01;
  r.scene.n_seg = 4;
  r.methods = {"lecture", "full-eigen-clamp", "no-projection", "symplectic-euler"};
  auto row = [&](const char* m, double h, double wall, double error, const char* failure) {
    StudyRow s;
    s.method = m;
    s.h = h;
    s.tol = r.scene.tol;
    s.n_seg = r.scene.n_seg;
    s.wall_s = wall;
    s.error = error;
    s.failure = failure;
    r.rows.push_back(s);
  };
  for (double h : {0.04, 0.02, 0.01}) {
    row("lecture", h, 0.01 / h, 2.0 * h, "ok");
    row("full-eigen-clamp", h, 0.05 / h, 2.0 * h, "ok");
    row("no-projection", h, 0.003 / h, 4.0 * h, "ok");
    row("symplectic-euler", h / 10, 1.0, NAN, "penetrated");
  }
  r.convergence.push_back({"neo-hookean", 1.0, 9, 0.02, 0.16, true, true});
  r.smooth_slope = 1.01;
  r.lecture_slope = 0.18;
  return r;
}

TEST(StudySlides, SixteenByNineLargeTypeTheMethodsThatRanAndATakeawayTitle) {
  const StudyResult r = three_methods();
  // At 4% error (the largest of the smallest errors) lecture needs 0.5 s/s at h = 0.02,
  // no-projection 0.3 s/s at h = 0.01, full-eigen-clamp 2.5 s/s: no-projection is fastest.
  EXPECT_EQ(speed_takeaway(r),
            "At 4% error no-projection is fastest, full-eigen-clamp 8.3\u00d7 slower; "
            "symplectic-euler fails at every h");
  EXPECT_EQ(convergence_takeaway(r),
            "Implicit Euler without contact: first order (slope 1.01); with contact: slope 0.18; "
            "symplectic-euler fails at every h");
  const std::vector<Slide> slides = study_slides(r);
  ASSERT_EQ(slides.size(), 2u);
  for (const Slide& s : slides) {
    const auto canvas = chart_canvas({s.chart}, ChartFormat::Png);
    EXPECT_EQ(canvas->width(), 1920) << s.name;
    EXPECT_EQ(canvas->height(), 1080) << s.name << ": 16:9, nothing added below";
    EXPECT_TRUE(s.chart.notes.empty());
    std::vector<std::string> labels;
    for (const Series& series : s.chart.series)
      if (!series.x.empty() && series.markers) labels.push_back(series.label);
    EXPECT_EQ(labels, (std::vector<std::string>{"lecture", "full-eigen-clamp", "no-projection"}))
        << s.name << ": the methods with a point, by their short names";
    // Large type: the title at least 48 px tall, every tick label at least 30 px.
    double title_h = 0.0, smallest = 1e9;
    for (const TextItem& t : canvas->texts()) {
      if (s.chart.title.find(t.text) == 0) title_h = std::max(title_h, t.y1 - t.y0);
      if (t.text == "10") smallest = std::min(smallest, t.y1 - t.y0);
    }
    EXPECT_GE(title_h, 48.0) << s.name;
    EXPECT_GE(smallest, 30.0) << s.name;
  }
  EXPECT_EQ(slides[0].chart.title, speed_takeaway(r));
  // --methods: a subset is what the slide shows.
  StudyResult two = r;
  two.methods = {"lecture", "full-eigen-clamp"};
  EXPECT_EQ(speed_takeaway(two),
            "At 2% error lecture is fastest, full-eigen-clamp 5.0\u00d7 slower");
  EXPECT_EQ(study_slides(two)[0].chart.series.size(), 2u);
}

TEST(StudyChart, ErrorsThatDoNotConvergeDrawNoFrontAndSaySo) {
  StudyResult r = three_methods();
  const auto fronts = [](const ChartSpec& c) {
    int n = 0;
    for (const Series& s : c.series) n += s.label.starts_with("Pareto front");
    return n;
  };
  EXPECT_EQ(fronts(study_panels(r)[0]), 1);
  EXPECT_EQ(study_panels(r)[0].title.find("CONVERGE"), std::string::npos);
  // stack --quick: errors of 20-50% of the side that do not fall with h.
  for (StudyRow& row : r.rows)
    if (row.failure == "ok") row.error = 0.2 + 0.3 * std::abs(std::sin(1e3 * row.h));
  r.convergence = {{"neo-hookean", -0.04, 9, 0.2, 0.5, true, false}};
  const std::vector<ChartSpec> panels = study_panels(r);
  EXPECT_EQ(fronts(panels[0]), 0) << "no front from errors that rank nothing";
  EXPECT_NE(panels[0].title.find("ERRORS DO NOT CONVERGE WITH h"), std::string::npos)
      << panels[0].title;
  EXPECT_NE(panels[0].title.find("neo-hookean (slope -0.04)"), std::string::npos);
  EXPECT_NE(panels[1].title.find("ERRORS DO NOT CONVERGE WITH h"), std::string::npos);
  EXPECT_NE(speed_takeaway(r).find(
                "do not converge with h (20-50% of the side, slope -0.04): they rank no method"),
            std::string::npos)
      << speed_takeaway(r);
}

StabilityCell cell(const std::string& method, Verdict v, double min_det_f) {
  StabilityCell c;
  c.method = method;
  c.scene = "s";
  c.verdict = v;
  c.min_det_f = min_det_f;
  c.h = 0.01;
  c.fail_step = v == Verdict::Ok ? -1 : 36;
  c.frame.x = VecX::Zero(6);
  c.frame.mesh.triangles = {{0, 1, 2}};
  c.frame.det_f = {1.0};
  return c;
}

StabilityResult small_sheet() {
  StabilityResult r;
  r.methods = {"lecture", "stable-neo-hookean", "symplectic-euler"};
  r.method_labels = r.methods;
  r.scenes = {"stress-soft", "stress-stiff"};
  r.scene_labels = {"E = 1e3 Pa", "E = 1e8 Pa"};
  r.cells = {cell("lecture", Verdict::Ok, 0.31),
             cell("lecture", Verdict::Ok, 0.87),
             cell("stable-neo-hookean", Verdict::InvertedAllowed, -0.2),
             cell("stable-neo-hookean", Verdict::Ok, 0.9),
             cell("symplectic-euler", Verdict::Inverted, -0.1),
             cell("symplectic-euler", Verdict::BlewUp, 0.5)};
  return r;
}

TEST(StabilitySheet, AnAllowedInversionIsNotAFailureAndOkCellsDiffer) {
  EXPECT_EQ(cell_class(Verdict::InvertedAllowed), CellClass::InversionAllowed);
  EXPECT_EQ(cell_class(Verdict::Inverted), CellClass::Failed);
  EXPECT_STREQ(verdict_name(Verdict::InvertedAllowed), "inverted-allowed");
  const StabilityResult r = small_sheet();
  const auto sheet = contact_sheet(r, ChartFormat::Svg);
  EXPECT_TRUE(has_text(*sheet, "inverted, allowed"));
  EXPECT_TRUE(has_text(*sheet, "min det F 0.31"));
  EXPECT_TRUE(has_text(*sheet, "min det F 0.87")) << "two ok cells read differently";
  const Rgb allowed = cell_class_color(CellClass::InversionAllowed),
            failed = cell_class_color(CellClass::Failed);
  EXPECT_FALSE(allowed.r == failed.r && allowed.g == failed.g && allowed.b == failed.b);
  EXPECT_LT(allowed.r, allowed.b) << "neutral blue, not red";

  // The summary slide: 16:9, the takeaway as the title, an ok cell's smallest det F.
  const auto summary = stability_summary(r, ChartFormat::Png);
  EXPECT_EQ(summary->width(), 1920);
  EXPECT_EQ(summary->height(), 1080);
  EXPECT_EQ(stability_takeaway(r),
            "The lecture's method is ok on all 2 scenes it can start; symplectic-euler fails on "
            "2 of 2");
  EXPECT_TRUE(has_text(*summary, stability_takeaway(r)));
  EXPECT_EQ(summary_cell_text(r.at(0, 0)), "0.31");
  EXPECT_EQ(summary_cell_text(r.at(0, 1)), "0.87");
  EXPECT_EQ(summary_cell_text(r.at(1, 0)), "inv. (allowed)");
  EXPECT_EQ(summary_cell_text(r.at(2, 1)), "blew-up");
  for (const std::string& m : r.methods) EXPECT_TRUE(has_text(*summary, m)) << m;
}

// The 64x64 fold at thumbnail size: its colour shows (det F = 1 is white), its edges do
// not turn it black.
TEST(StabilitySheet, AFineMeshShowsItsColourNotItsEdges) {
  for (int n : {8, 64}) {
    Frame f;
    const Mesh mesh = square_mesh(1.0, n);
    f.mesh.triangles = mesh.triangles;
    f.x.resize(2 * mesh.node_count());
    for (int i = 0; i < mesh.node_count(); ++i) f.x.segment<2>(2 * i) = mesh.rest[i];
    f.det_f.assign(mesh.triangles.size(), 1.0);
    f.has_ground = true;
    f.ground_y = -0.5;
    const double size = 150;
    Canvas canvas(size, size, ChartFormat::Png);
    draw_frame(canvas, f, 0, 0, size);
    const std::string png = canvas.finish();
    int w = 0, h = 0, c = 0;
    unsigned char* data = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()),
                                                static_cast<int>(png.size()), &w, &h, &c, 3);
    ASSERT_NE(data, nullptr);
    // The body covers pixels x 31..119, y 57..146 (1.7 side across the cell, 0.05 side
    // of ground below it): its inner part.
    double sum = 0.0;
    int count = 0;
    for (int y = 70; y < 130; ++y)
      for (int x = 45; x < 105; ++x, ++count)
        for (int k = 0; k < 3; ++k) sum += data[3 * (y * w + x) + k] / 3.0;
    stbi_image_free(data);
    const double mean = sum / count;
    if (n == 64)
      EXPECT_GT(mean, 230.0) << "the 64x64 body is white, not darkened by its edges";
    else
      EXPECT_LT(mean, 250.0) << "an 8x8 mesh still shows its edges";
  }
}

// A sweep of 3 methods x 7 scenes, 13 of whose runs failed or inverted as allowed: the
// sheet's pages are 16:9 and show those 13 runs, each once, large, with their method, scene
// and verdict in large type; no ok or n/a run.
TEST(StabilitySheetPages, SixteenByNineLargeThumbnailsOfEveryRunThatFailedOrInverted) {
  StabilityResult r;
  r.methods = {"lecture", "symplectic-euler", "arap"};
  r.method_labels = r.methods;
  for (int k = 0; k < 7; ++k) {
    r.scenes.push_back("stress-" + std::to_string(k));
    r.scene_labels.push_back("scene number " + std::to_string(k));
  }
  const Mesh mesh = square_mesh(1.0, 4);
  for (const std::string& m : r.methods)
    for (int k = 0; k < 7; ++k) {
      const Verdict v = m == "lecture"            ? (k == 6 ? Verdict::NotApplicable : Verdict::Ok)
                        : m == "symplectic-euler" ? (k == 0 ? Verdict::BlewUp : Verdict::Penetrated)
                        : k < 6                   ? Verdict::InvertedAllowed
                                                  : Verdict::Ok;
      StabilityCell c = cell(m, v, 0.5);
      c.scene = r.scenes[k];
      c.frame.mesh.triangles = mesh.triangles;
      c.frame.x.resize(2 * mesh.node_count());
      for (int i = 0; i < mesh.node_count(); ++i) c.frame.x.segment<2>(2 * i) = mesh.rest[i];
      c.frame.det_f.assign(mesh.triangles.size(), 0.8);
      c.frame.has_ground = true;
      c.frame.ground_y = -0.5;
      r.cells.push_back(c);
    }
  const std::vector<const StabilityCell*> expected = sheet_runs(r);
  ASSERT_EQ(expected.size(), 13u);
  const auto pages = stability_sheet_pages(r, ChartFormat::Svg);
  ASSERT_EQ(pages.size(), (13 + kSheetRunsPerPage - 1) / kSheetRunsPerPage);
  std::vector<const StabilityCell*> shown;
  for (const SheetPage& page : pages) {
    EXPECT_EQ(page.canvas->width(), 1920);
    EXPECT_EQ(page.canvas->height(), 1080);
    EXPECT_TRUE(has_text(*page.canvas, page.title));
    for (size_t i = 0; i < page.thumbs.size(); ++i) {
      const SheetThumb& t = page.thumbs[i];
      shown.push_back(t.cell);
      EXPECT_GE(t.x1 - t.x0, 400) << "a thumbnail a class can see";
      EXPECT_GE(t.y1 - t.y0, 250);
      EXPECT_GE(t.x0, 0);
      EXPECT_GE(t.y0, 0);
      EXPECT_LE(t.x1, 1920);
      EXPECT_LE(t.y1, 1080);
      for (size_t j = 0; j < i; ++j) {
        const SheetThumb& o = page.thumbs[j];
        EXPECT_TRUE(t.x0 >= o.x1 || o.x0 >= t.x1 || t.y0 >= o.y1 || o.y0 >= t.y1)
            << "thumbnails " << j << " and " << i << " overlap";
      }
      // Its method, scene and verdict under it, in large type.
      const std::string label = r.scene_labels[t.cell->scene.back() - '0'];
      for (const std::string& words : {t.cell->method, label, sheet_verdict_text(*t.cell)}) {
        bool found = false;
        for (const TextItem& item : page.canvas->texts())
          if (item.text == words && item.y0 >= t.y1 && item.y0 < t.y1 + 150 && item.x0 >= t.x0 &&
              item.x1 <= t.x1) {
            found = true;
            EXPECT_GE(item.y1 - item.y0, 24.0) << words << ": large type";
          }
        EXPECT_TRUE(found) << words << " under its thumbnail";
      }
    }
  }
  EXPECT_EQ(shown, expected) << "every run that failed or inverted, each once, in table order";
  for (const StabilityCell* c : shown)
    EXPECT_TRUE(cell_class(c->verdict) == CellClass::Failed ||
                cell_class(c->verdict) == CellClass::InversionAllowed);
  EXPECT_EQ(sheet_verdict_text(*expected[0]), "blew-up at t = 0.36 s");
  EXPECT_EQ(pages[0].title,
            "symplectic-euler fails on 7 of 7; arap inverts on 6 of 7, as its model allows");
  EXPECT_TRUE(has_text(*pages[0].canvas, "Not shown: 7 ok runs, 1 n/a"));

  // Nothing failed: one page that says so.
  StabilityResult calm = r;
  for (StabilityCell& c : calm.cells)
    if (c.verdict != Verdict::NotApplicable) c.verdict = Verdict::Ok;
  const auto calm_pages = stability_sheet_pages(calm, ChartFormat::Svg);
  ASSERT_EQ(calm_pages.size(), 1u);
  EXPECT_TRUE(calm_pages[0].thumbs.empty());
  EXPECT_EQ(calm_pages[0].title, "Every method is ok on every scene it can start");
}

// One palette (app/study/stability_palette.h): the red that frames a failed run on the
// sheet is the red that fills a failed cell on the slide.
TEST(StabilitySheetPages, TheSheetsRedIsTheSlidesRed) {
  const auto summary = stability_summary(small_sheet(), ChartFormat::Png);
  const std::string png = summary->finish();
  int w = 0, h = 0, c = 0;
  unsigned char* data = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()),
                                              static_cast<int>(png.size()), &w, &h, &c, 3);
  ASSERT_NE(data, nullptr);
  const Rgb red = cell_class_color(CellClass::Failed);
  const int want[3] = {static_cast<int>(std::lround(255 * red.r)),
                       static_cast<int>(std::lround(255 * red.g)),
                       static_cast<int>(std::lround(255 * red.b))};
  long count = 0;
  for (int i = 0; i < w * h; ++i)
    count += std::abs(data[3 * i] - want[0]) <= 1 && std::abs(data[3 * i + 1] - want[1]) <= 1 &&
             std::abs(data[3 * i + 2] - want[2]) <= 1;
  stbi_image_free(data);
  EXPECT_GT(count, 10000) << "the slide's two failed cells are filled with the sheet's red";
}

}  // namespace
}  // namespace invfree
