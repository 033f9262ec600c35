// The chart library: pixels of known primitives, text, log-axis ticks and mapping, the
// Pareto front, and a PNG round trip through an independent decoder (stb_image).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

#include "app/plot/axis.h"
#include "app/plot/chart.h"
#include "app/plot/raster.h"
#include "app/study/study_chart.h"

namespace invfree {
namespace {

constexpr Rgb kWhite{1.0f, 1.0f, 1.0f};
constexpr Rgb kRed{1.0f, 0.0f, 0.0f};

bool is_white(const Image& img, int x, int y) {
  const auto p = pixel_rgb(img, x, y);
  return p[0] == 255 && p[1] == 255 && p[2] == 255;
}

TEST(Raster, HorizontalLineCoversItsWidthAndNothingElse) {
  Image img = make_image(100, 60, kWhite);
  draw_line(img, {10.0, 30.0}, {90.0, 30.0}, 4.0, kRed);  // covers rows 28..31 fully
  for (int y = 28; y <= 31; ++y)
    EXPECT_EQ(pixel_rgb(img, 50, y), (std::array<int, 3>{255, 0, 0})) << y;
  EXPECT_TRUE(is_white(img, 50, 26));
  EXPECT_TRUE(is_white(img, 50, 33));
  EXPECT_TRUE(is_white(img, 5, 30)) << "round cap ends 2 px past the end point";
  EXPECT_FALSE(is_white(img, 91, 30));
  // Antialiasing: a line through pixel centres at half-integer width leaves partial rows.
  Image aa = make_image(40, 40, kWhite);
  draw_line(aa, {0.0, 20.0}, {40.0, 20.0}, 1.0, kRed);
  const auto above = pixel_rgb(aa, 20, 19), below = pixel_rgb(aa, 20, 20);
  EXPECT_EQ(above[0], 255);
  EXPECT_GT(above[1], 0);
  EXPECT_LT(above[1], 255) << "half covered";
  EXPECT_EQ(below[1], above[1]) << "symmetric about y = 20";
}

TEST(Raster, PolylineJointsAreNotDrawnTwice) {
  Image img = make_image(60, 60, kWhite);
  draw_polyline(img, {{10, 10}, {30, 30}, {50, 10}}, 3.0, kRed, 0.5);
  // The joint pixel is covered by both segments; half-transparent red must not stack.
  EXPECT_EQ(pixel_rgb(img, 30, 29), pixel_rgb(img, 20, 19));
}

TEST(Raster, MarkersHaveTheirShape) {
  Image img = make_image(80, 40, kWhite);
  draw_marker(img, {20.0, 20.0}, 8.0, MarkerShape::Circle, kRed, kRed);
  draw_marker(img, {60.0, 20.0}, 8.0, MarkerShape::Square, kRed, kRed);
  EXPECT_EQ(pixel_rgb(img, 20, 20), (std::array<int, 3>{255, 0, 0}));
  // Circle of radius 8: (20 + 6.5, 20 + 6.5) pixel centre is 9.2 from the centre: outside.
  EXPECT_TRUE(is_white(img, 26, 26));
  // Square of half-size 0.85 * 8 = 6.8: that corner pixel is inside.
  EXPECT_FALSE(is_white(img, 60 + 5, 20 + 5));
  EXPECT_TRUE(is_white(img, 60 + 9, 20));
}

TEST(Raster, MeshHasNoSeamsBetweenTriangles) {
  Image img = make_image(40, 40, kWhite);
  // Two triangles of one colour sharing the diagonal of a square.
  fill_mesh(img, {{5, 5}, {35, 5}, {35, 35}, {5, 35}}, {{0, 1, 2}, {0, 2, 3}}, {kRed, kRed});
  for (int i = 6; i < 34; ++i)
    EXPECT_EQ(pixel_rgb(img, i, i), (std::array<int, 3>{255, 0, 0})) << i;
  EXPECT_TRUE(is_white(img, 2, 20));
}

TEST(Raster, TextInksWhereItIsDrawn) {
  Image img = make_image(200, 60, kWhite);
  draw_text(img, "Wg 10\u207b\u00b3 \u03bd", 10, 40, 24, {0, 0, 0});
  int inked = 0, left = 200, right = 0;
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 200; ++x)
      if (!is_white(img, x, y)) {
        ++inked;
        left = std::min(left, x);
        right = std::max(right, x);
      }
  EXPECT_GT(inked, 100);
  EXPECT_GE(left, 10);
  EXPECT_NEAR(right, 10 + text_width("Wg 10\u207b\u00b3 \u03bd", 24), 3.0);
  EXPECT_LT(text_width("ii", 20), text_width("WW", 20));
  EXPECT_NEAR(text_width("abc", 40), 2.0 * text_width("abc", 20), 1.0);
  const auto lines =
      wrap_text("one two three four five six", 20, text_width("one two three", 20) + 1);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "one two three");
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

TEST(Chart, LogAxisPlacesDecadesEvenly) {
  ChartSpec spec;
  spec.log_x = true;
  spec.series.push_back({"", {1.0, 10.0, 100.0, 1000.0}, {5.0, 5.0, 5.0, 5.0}, kRed, true, false});
  const Image img = render_chart(spec);
  // Centres of the red markers along the row through them.
  std::vector<double> centres;
  int row = -1;
  for (int y = 0; y < img.height && row < 0; ++y)
    for (int x = 0; x < img.width; ++x)
      if (pixel_rgb(img, x, y) == std::array<int, 3>{255, 0, 0}) {
        row = y + 3;
        break;
      }
  ASSERT_GE(row, 0) << "no marker drawn";
  int run_start = -1;
  for (int x = 0; x <= img.width; ++x) {
    const bool red =
        x < img.width && pixel_rgb(img, x, row)[0] > 200 && pixel_rgb(img, x, row)[1] < 80;
    if (red && run_start < 0) run_start = x;
    if (!red && run_start >= 0) {
      centres.push_back(0.5 * (run_start + x - 1));
      run_start = -1;
    }
  }
  ASSERT_EQ(centres.size(), 4u);
  const double step = centres[1] - centres[0];
  EXPECT_GT(step, 100.0);
  EXPECT_NEAR(centres[2] - centres[1], step, 1.01);
  EXPECT_NEAR(centres[3] - centres[2], step, 1.01);
}

TEST(Chart, SkipsPointsALogAxisCannotShowAndNeverFails) {
  ChartSpec spec;
  spec.log_y = true;
  spec.series.push_back({"bad", {1.0, 2.0, 3.0}, {-1.0, 0.0, std::nan("")}, kRed, true, true});
  const Image img = render_chart(spec);
  EXPECT_EQ(img.width, 1280);
  EXPECT_EQ(img.height, 800);
  ChartSpec empty;
  EXPECT_EQ(render_chart(empty).rgba.size(), 1280u * 800u * 4u);
}

TEST(Chart, ParetoFrontKeepsOnlyUnbeatenPoints) {
  // (1,5) (2,3) (3,4) (4,1) (5,2): (3,4) is beaten by (2,3), (5,2) by (4,1).
  const auto front = pareto_front({1, 2, 3, 4, 5, NAN}, {5, 3, 4, 1, 2, 0});
  EXPECT_EQ(front, (std::vector<size_t>{0, 1, 3}));
}

TEST(Png, RoundTripsThroughAnIndependentDecoder) {
  Image img = make_image(37, 23, {0.2f, 0.4f, 0.6f});
  draw_line(img, {0, 0}, {36, 22}, 2.0, kRed);
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
  const Image img = make_image(4, 4, kWhite);
  const std::string e = write_png("/nonexistent-dir/x.png", img);
  EXPECT_NE(e.find("/nonexistent-dir/x.png"), std::string::npos) << e;
  EXPECT_NE(write_png("/tmp/never.png", Image{}), "");
}

}  // namespace
}  // namespace invfree
