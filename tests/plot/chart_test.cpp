// The chart library and the study's charts, tested for what they mean rather than for
// Cairo's pixels: the text a chart writes (the canvas logs every piece with its box),
// where the axes put the data, that notes stay inside the drawing, one Pareto front per
// material model, the mesh panel against n_seg, and the files in the three formats (a
// PNG decoded by an independent decoder, SVG and PDF by their headers).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

#include "app/plot/axis.h"
#include "app/plot/chart.h"
#include "app/study/study_chart.h"

namespace invfree {
namespace {

constexpr Rgb kRed{1.0f, 0.0f, 0.0f};

bool has_text(const Canvas& canvas, const std::string& text) {
  for (const TextItem& t : canvas.texts())
    if (t.text.find(text) != std::string::npos) return true;
  return false;
}

TEST(Canvas, PngHasItsSizeAndTheColoursDrawn) {
  Canvas canvas(37, 23, ChartFormat::Png);
  canvas.fill_rect(10, 5, 20, 15, kRed);
  const std::string png = canvas.finish();
  int w = 0, h = 0, c = 0;
  unsigned char* data = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()),
                                              static_cast<int>(png.size()), &w, &h, &c, 4);
  ASSERT_NE(data, nullptr);
  EXPECT_EQ(w, 37);
  EXPECT_EQ(h, 23);
  auto rgb = [&](int x, int y) {
    const unsigned char* p = data + 4 * (y * w + x);
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  EXPECT_EQ(rgb(15, 10), (std::array<int, 3>{255, 0, 0}));
  EXPECT_EQ(rgb(2, 2), (std::array<int, 3>{255, 255, 255})) << "the background is white";
  EXPECT_EQ(rgb(25, 10), (std::array<int, 3>{255, 255, 255}));
  stbi_image_free(data);
}

TEST(Canvas, VectorFormatsAreWhatTheySayTheyAre) {
  for (ChartFormat f : {ChartFormat::Svg, ChartFormat::Pdf}) {
    Canvas canvas(300, 200, f);
    canvas.text("label", 10, 50, 20, {0, 0, 0});
    const std::string bytes = canvas.finish();
    if (f == ChartFormat::Svg) {
      EXPECT_NE(bytes.find("<svg"), std::string::npos);
      EXPECT_NE(bytes.find("width=\"300"), std::string::npos);
    } else {
      EXPECT_EQ(bytes.substr(0, 5), "%PDF-");
    }
  }
  EXPECT_EQ(parse_chart_format("svg"), ChartFormat::Svg);
  EXPECT_EQ(parse_chart_format("jpeg"), std::nullopt);
  EXPECT_STREQ(chart_extension(ChartFormat::Pdf), "pdf");
}

TEST(Canvas, TextIsMeasuredAndLoggedWithItsBox) {
  Canvas canvas(400, 100, ChartFormat::Png);
  const std::string s = "Wg 10\u207b\u00b3 \u03bd";
  canvas.text(s, 200, 60, 24, {0, 0, 0}, Align::Center);
  ASSERT_EQ(canvas.texts().size(), 1u);
  const TextItem& t = canvas.texts()[0];
  EXPECT_NEAR(t.x1 - t.x0, text_width(s, 24), 1e-9);
  EXPECT_NEAR((t.x0 + t.x1) / 2.0, 200.0, 1e-9) << "centred on its anchor";
  EXPECT_LT(t.y0, 60.0);
  EXPECT_GT(t.y1, 60.0) << "the baseline lies inside the box (descenders below it)";
  EXPECT_NEAR(t.y1 - t.y0, 24.0, 1.0) << "size is the font's ascent + descent";
  EXPECT_LT(text_width("ii", 20), text_width("WW", 20));
  EXPECT_NEAR(text_width("abc", 40), 2.0 * text_width("abc", 20), 1e-6);
  const auto lines =
      wrap_text("one two three four five six", 20, text_width("one two three", 20) + 1);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "one two three");
  canvas.text("up", 30, 50, 20, {0, 0, 0}, Align::Center, true);
  const TextItem& v = canvas.texts()[1];
  EXPECT_GT(v.y1 - v.y0, v.x1 - v.x0) << "vertical text is taller than wide";
}

TEST(Axis, LogTicksAreDecadesWithMinorTicksBetween) {
  const AxisRange r = axis_range({1e-3, 100.0}, true);
  EXPECT_LT(r.lo, -3.0);
  EXPECT_GT(r.hi, 2.0);
  std::vector<double> decades;
  int minor = 0, expected_minor = 0;
  for (int k = -5; k <= 4; ++k)
    for (int m = 2; m <= 9; ++m) {
      const double a = k + std::log10(double(m));
      expected_minor += a >= r.lo && a <= r.hi;
    }
  for (const Tick& t : axis_ticks(r)) {
    if (t.major) {
      decades.push_back(t.value);
      EXPECT_TRUE(t.decade_label);
      EXPECT_NEAR(std::pow(10.0, t.exponent), t.value, 1e-12 * t.value);
    } else {
      ++minor;
      EXPECT_FALSE(t.labelled);
    }
  }
  ASSERT_EQ(decades.size(), 6u);
  for (size_t i = 0; i < decades.size(); ++i)
    EXPECT_NEAR(decades[i], std::pow(10.0, -3.0 + i), 1e-15);
  EXPECT_EQ(minor, expected_minor);
  EXPECT_GE(minor, 5 * 8) << "2..9 in each of the five whole decades";
}

TEST(Axis, NarrowLogRangesStillGetAtLeastTwoLabels) {
  for (auto [lo, hi] : {std::pair{0.085, 0.095}, std::pair{2.0, 30.0}, std::pair{0.3, 0.9}}) {
    int labelled = 0;
    for (const Tick& t : axis_ticks(axis_range({lo, hi}, true))) labelled += t.labelled;
    EXPECT_GE(labelled, 2) << lo << ".." << hi;
  }
}

TEST(Axis, LinearTicksUseNiceSteps) {
  std::vector<double> v;
  for (const Tick& t : axis_ticks(axis_range({0.0, 10.0}, false))) v.push_back(t.value);
  EXPECT_EQ(v, (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(format_tick(0.05), "0.05");
}

TEST(Chart, LogAxisLabelsItsDecadesEvenly) {
  ChartSpec spec;
  spec.log_x = true;
  spec.x_label = "x axis";
  spec.y_label = "y axis";
  spec.title = "the title";
  spec.series.push_back({"", {1.0, 10.0, 100.0, 1000.0}, {5.0, 5.0, 5.0, 5.0}, kRed, true, false});
  const auto canvas = chart_canvas({spec}, ChartFormat::Png);
  for (const char* s : {"x axis", "y axis", "the title"}) EXPECT_TRUE(has_text(*canvas, s)) << s;
  // The decade labels "10" (with their exponents beside them) below the plot, left to right.
  std::vector<double> left;
  for (const TextItem& t : canvas->texts())
    if (t.text == "10" && t.y0 > canvas->height() * 0.8) left.push_back(t.x0);
  std::sort(left.begin(), left.end());
  ASSERT_EQ(left.size(), 4u);
  const double step = left[1] - left[0];
  EXPECT_GT(step, 100.0);
  EXPECT_NEAR(left[2] - left[1], step, 1e-6);
  EXPECT_NEAR(left[3] - left[2], step, 1e-6);
}

// Given ticks replace the automatic ones: thread counts 1 and 2 on a linear axis get "1"
// and "2" and no 1-2-5 ticks between them (no "1.5" threads); 1 to 16 on log axes get
// every count labelled and no decade label.
TEST(Chart, GivenTicksAreTheOnlyTicks) {
  // The x axis's labels: below the plot, right of the y axis's labels.
  const auto labels_below = [](const Canvas& canvas, double below) {
    std::vector<std::string> out;
    for (const TextItem& t : canvas.texts())
      if (t.y0 > below && t.x0 > 0.1 * canvas.width()) out.push_back(t.text);
    return out;
  };
  ChartSpec linear;
  linear.series.push_back({"", {1.0, 2.0}, {1.0, 1.64}, kRed});
  linear.x_ticks = {2.0, 1.0, 2.0};  // unsorted, repeated: drawn once each, in order
  const auto a = chart_canvas({linear}, ChartFormat::Png);
  const std::vector<std::string> below_a = labels_below(*a, a->height() * 0.85);
  EXPECT_EQ(std::count(below_a.begin(), below_a.end(), "1"), 1);
  EXPECT_EQ(std::count(below_a.begin(), below_a.end(), "2"), 1);
  for (const std::string& t : below_a) EXPECT_EQ(t.find('.'), std::string::npos) << t;

  ChartSpec sweep;
  sweep.log_x = sweep.log_y = true;
  sweep.series.push_back({"", {1, 2, 4, 8, 16}, {1.0, 1.9, 3.5, 5.8, 7.9}, kRed});
  sweep.x_ticks = sweep.y_ticks = {1, 2, 4, 8, 16};
  const auto b = chart_canvas({sweep}, ChartFormat::Png);
  const std::vector<std::string> below_b = labels_below(*b, b->height() * 0.85);
  for (const char* t : {"1", "2", "4", "8", "16"})
    EXPECT_EQ(std::count(below_b.begin(), below_b.end(), t), 1) << t;
  EXPECT_EQ(std::count(below_b.begin(), below_b.end(), "10"), 0);
  // The y axis too: every count's label left of the plot.
  int left = 0;
  for (const TextItem& t : b->texts())
    if (t.x1 < b->width() * 0.15 && (t.text == "4" || t.text == "8" || t.text == "16")) ++left;
  EXPECT_EQ(left, 3);
  // Equal ratios, equal steps: 1 -> 2 -> 4 -> 8 -> 16 evenly spaced on the log axis.
  std::vector<double> x;
  for (const TextItem& t : b->texts())
    if (t.y0 > b->height() * 0.85 && t.x0 > 0.1 * b->width() &&
        t.text.find_first_not_of("0123456789") == std::string::npos)
      x.push_back(0.5 * (t.x0 + t.x1));
  std::sort(x.begin(), x.end());
  ASSERT_EQ(x.size(), 5u);
  for (size_t k = 2; k < x.size(); ++k) EXPECT_NEAR(x[k] - x[k - 1], x[1] - x[0], 1.0);
}

TEST(Chart, NotesStayInsideTheDrawing) {
  ChartSpec spec;
  spec.series.push_back({"a series with a label", {1.0, 2.0}, {1.0, 2.0}, kRed, true, true});
  std::string long_note;
  for (int i = 0; i < 60; ++i) long_note += "a long caption that wraps onto many lines ";
  spec.notes = {long_note, long_note, "the last line"};
  for (ChartFormat f : {ChartFormat::Png, ChartFormat::Svg}) {
    const auto canvas = chart_canvas({spec, spec}, f);
    EXPECT_GT(canvas->height(), 2 * 800) << "the notes make the panels taller";
    int last = 0;
    for (const TextItem& t : canvas->texts()) {
      EXPECT_GE(t.x0, 0.0) << t.text;
      EXPECT_GE(t.y0, 0.0) << t.text;
      EXPECT_LE(t.x1, canvas->width()) << t.text;
      EXPECT_LE(t.y1, canvas->height()) << t.text;
      last += t.text == "the last line";
    }
    EXPECT_EQ(last, 2) << "each panel's last note is drawn";
  }
}

TEST(Chart, SkipsPointsALogAxisCannotShowAndNeverFails) {
  ChartSpec spec;
  spec.log_y = true;
  spec.series.push_back({"bad", {1.0, 2.0, 3.0}, {-1.0, 0.0, std::nan("")}, kRed, true, true});
  const auto canvas = chart_canvas({spec}, ChartFormat::Png);
  EXPECT_EQ(canvas->width(), 1280);
  EXPECT_EQ(canvas->height(), 800);
  EXPECT_FALSE(canvas->finish().empty());
  EXPECT_FALSE(chart_canvas({ChartSpec{}}, ChartFormat::Png)->finish().empty());
}

TEST(Chart, ParetoFrontKeepsOnlyUnbeatenPoints) {
  // (1,5) (2,3) (3,4) (4,1) (5,2): (3,4) is beaten by (2,3), (5,2) by (4,1).
  const auto front = pareto_front({1, 2, 3, 4, 5, NAN}, {5, 3, 4, 1, 2, 0});
  EXPECT_EQ(front, (std::vector<size_t>{0, 1, 3}));
}

// A study result with rows in the h sweep (tol and n_seg of the scene).
StudyResult synthetic_study() {
  StudyResult r;
  r.scene.name = "test";
  r.scene.tol = 1e-4;
  r.scene.h = 0.01;
  r.scene.n_seg = 8;
  auto row = [&](const char* method, double h, double wall, double error) {
    StudyRow s;
    s.method = method;
    s.h = h;
    s.tol = r.scene.tol;
    s.n_seg = r.scene.n_seg;
    s.wall_s = wall;
    s.error = error;
    s.failure = "ok";
    r.rows.push_back(s);
  };
  row("lecture", 0.02, 1.0, 0.1);
  row("lecture", 0.01, 2.0, 0.05);
  row("full-eigen-clamp", 0.01, 3.0, 0.05);
  // ARAP, against its own reference: faster and "more accurate" than everything above.
  row("arap", 0.02, 0.5, 0.001);
  row("arap", 0.01, 0.9, 0.0005);
  return r;
}

const Series* find_series(const ChartSpec& spec, const std::string& prefix) {
  for (const Series& s : spec.series)
    if (s.label.starts_with(prefix)) return &s;
  return nullptr;
}

TEST(StudyChart, OneParetoFrontPerModelLabelledWithH) {
  const StudyResult r = synthetic_study();
  const ChartSpec speed = study_panels(r)[0];
  const Series* neo = find_series(speed, "Pareto front, neo-hookean");
  const Series* arap = find_series(speed, "Pareto front, arap");
  ASSERT_NE(neo, nullptr);
  ASSERT_NE(arap, nullptr);
  EXPECT_EQ(find_series(speed, "Pareto front, linear"), nullptr) << "no points, no front";
  // The neo-Hookean front is made of neo-Hookean points only, though ARAP's lie below.
  EXPECT_EQ(neo->x, (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(neo->y, (std::vector<double>{0.1, 0.05}));
  EXPECT_EQ(neo->point_labels, (std::vector<std::string>{"h = 0.02", "h = 0.01"}));
  EXPECT_EQ(arap->x, (std::vector<double>{0.5, 0.9}));
  const auto canvas = chart_canvas(study_panels(r), ChartFormat::Svg);
  EXPECT_TRUE(has_text(*canvas, "h = 0.02"));
  EXPECT_TRUE(has_text(*canvas, "own reference"));
}

TEST(StudyChart, MeshPanelIsAgainstNSegAndSaysWhenItsRangeIsNarrow) {
  StudyResult r = synthetic_study();
  for (int n : {8, 16}) {
    StudyRow s;
    s.method = "lecture-mesh";
    s.h = r.scene.h;
    s.tol = r.scene.tol;
    s.n_seg = n;
    s.wall_s = n * 0.1;
    s.error = n == 8 ? 0.094 : 0.086;
    s.failure = "ok";
    r.rows.push_back(s);
  }
  ChartSpec mesh = sweeps_panels(r)[1];
  ASSERT_EQ(mesh.series.size(), 1u);
  EXPECT_EQ(mesh.series[0].x, (std::vector<double>{8.0, 16.0}));
  EXPECT_NE(mesh.x_label.find("n_seg"), std::string::npos);
  EXPECT_FALSE(mesh.log_x) << "n_seg on a linear axis";
  EXPECT_NE(mesh.title.find("narrow y range"), std::string::npos) << mesh.title;
  r.rows.back().error = 0.01;  // a factor of 9.4: not narrow
  mesh = sweeps_panels(r)[1];
  EXPECT_EQ(mesh.title.find("narrow"), std::string::npos) << mesh.title;
}

TEST(Png, RoundTripsThroughAnIndependentDecoder) {
  Image img{37, 23, std::vector<std::uint8_t>(37 * 23 * 4, 200)};
  img.rgba[4 * (5 * 37 + 7) + 1] = 123;
  const std::string path =
      (std::filesystem::temp_directory_path() / "invfree_chart_test.png").string();
  ASSERT_EQ(write_png(path, img), "");
  int w = 0, h = 0, c = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &c, 4);
  ASSERT_NE(data, nullptr);
  EXPECT_EQ(w, 37);
  EXPECT_EQ(h, 23);
  EXPECT_TRUE(std::equal(img.rgba.begin(), img.rgba.end(), data));
  stbi_image_free(data);
  std::filesystem::remove(path);
}

TEST(Png, ReportsUnwritablePathsAndEmptyImages) {
  const Image img{4, 4, std::vector<std::uint8_t>(64, 255)};
  const std::string e = write_png("/nonexistent-dir/x.png", img);
  EXPECT_NE(e.find("/nonexistent-dir/x.png"), std::string::npos) << e;
  EXPECT_NE(write_png("/tmp/never.png", Image{}), "");
}

}  // namespace
}  // namespace invfree
