// The landscape chart (app/landscape/landscape_chart.h): goldens of neo-Hookean alone and of
// the four models side by side (tests/landscape/goldens/, compared under image_compare.h's
// tolerance; INVFREE_UPDATE_GOLDENS=1 rewrites them: look at them before committing), and
// what the chart says where: the title with the model and the Lame parameters, the axis
// labels, the colour bar's unit and levels, the wall's label, all inside the drawing.
#include "app/landscape/landscape_chart.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "tests/render/image_compare.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

const Lame kLame = lame_from_young_poisson(1e5, 0.4);

std::string golden_dir() {
  return std::string(test::source_dir()) + "/tests/landscape/goldens";
}

test::RgbImage png_image(Canvas& canvas, const std::string& name) {
  const std::string path = ::testing::TempDir() + "/landscape_" + name + ".png";
  EXPECT_EQ(write_canvas(path, canvas), "");
  test::RgbImage image;
  EXPECT_TRUE(test::load_png(path, &image)) << path;
  std::remove(path.c_str());
  return image;
}

bool has_text(const Canvas& c, const std::string& needle) {
  for (const TextItem& t : c.texts())
    if (t.text.find(needle) != std::string::npos) return true;
  return false;
}

void expect_texts_inside(const Canvas& c) {
  for (const TextItem& t : c.texts()) {
    EXPECT_GE(t.x0, 0.0) << t.text;
    EXPECT_GE(t.y0, 0.0) << t.text;
    EXPECT_LE(t.x1, c.width()) << t.text;
    EXPECT_LE(t.y1, c.height()) << t.text;
  }
}

LandscapeChartSpec spec_of(std::vector<Model> models) {
  LandscapeChartSpec s;
  s.models = std::move(models);
  s.lame = kLame;
  return s;
}

// The goldens at a smaller size than the command's (plot_height 360, not 500): the same
// drawing code, a smaller file in the repository.
constexpr double kGoldenPlotHeight = 360.0;

TEST(LandscapeChart, NeoHookeanGolden) {
  LandscapeChartSpec s = spec_of({Model::NeoHookean});
  s.plot_height = kGoldenPlotHeight;
  auto canvas = landscape_chart(s, ChartFormat::Png);
  const std::string m = test::check_golden(png_image(*canvas, "nh"), "landscape_neo_hookean",
                                           golden_dir(), test::golden_failure_dir());
  EXPECT_TRUE(m.empty()) << m;
}

TEST(LandscapeChart, AllModelsGolden) {
  LandscapeChartSpec s =
      spec_of({Model::NeoHookean, Model::Linear, Model::Arap, Model::StableNeoHookean});
  s.plot_height = kGoldenPlotHeight;
  // Dots where a teacher would point: rest, a stretch, a squeeze, near the wall, inverted.
  s.points = {{1.0, 1.0}, {1.4, 0.9}, {0.8, 0.6}, {1.5, 0.05}, {1.3, -0.4}};
  s.points_caption = "Dots: five hand-placed points";
  auto canvas = landscape_chart(s, ChartFormat::Png);
  const std::string m = test::check_golden(png_image(*canvas, "all"), "landscape_all", golden_dir(),
                                           test::golden_failure_dir());
  EXPECT_TRUE(m.empty()) << m;
}

TEST(LandscapeChart, SaysWhatItShowsInsideTheDrawing) {
  auto canvas = landscape_chart(spec_of({Model::NeoHookean}), ChartFormat::Png);
  const Canvas& c = *canvas;
  EXPECT_TRUE(has_text(c, "neo-Hookean"));
  EXPECT_TRUE(has_text(c, "\u03bc = 35.7 kPa"));
  EXPECT_TRUE(has_text(c, "\u03bb = 143 kPa"));
  EXPECT_TRUE(has_text(c, "\u03a8(\u03c3\u2081, \u03c3\u2082)"));
  // Axis labels: exactly these words, once each.
  int s1 = 0, s2 = 0;
  for (const TextItem& t : c.texts()) {
    s1 += t.text == "\u03c3\u2081";
    s2 += t.text == "\u03c3\u2082";
  }
  EXPECT_EQ(s1, 1);
  EXPECT_EQ(s2, 1);
  // The colour bar: its unit, every level, the forbidden swatch.
  EXPECT_TRUE(has_text(c, "\u03a8 (Pa)"));
  for (const char* level : {"1 kPa", "3 kPa", "10 kPa", "30 kPa", "100 kPa", "300 kPa", "1 MPa"})
    EXPECT_TRUE(has_text(c, level)) << level;
  EXPECT_TRUE(has_text(c, "+\u221e (forbidden)"));
  // The wall, named on the plot and in the legend.
  EXPECT_TRUE(has_text(c, "\u03c3\u2081\u03c3\u2082 = 0: \u03a8 \u2192 +\u221e"));
  EXPECT_TRUE(has_text(c, "neo-Hookean's wall"));
  EXPECT_FALSE(has_text(c, "a triangle's"));  // no dots, no dot in the legend
  expect_texts_inside(c);
}

TEST(LandscapeChart, SideBySideNamesEveryModelAndWhyOnlyOneIsABarrier) {
  LandscapeChartSpec s =
      spec_of({Model::NeoHookean, Model::Linear, Model::Arap, Model::StableNeoHookean});
  s.points = {{1.0, 1.0}, {1.2, -0.3}};
  s.points_caption = "Dots: 2 triangles";
  auto canvas = landscape_chart(s, ChartFormat::Png);
  const Canvas& c = *canvas;
  for (const char* label : {"neo-Hookean", "linear", "ARAP", "stable neo-Hookean"})
    EXPECT_TRUE(has_text(c, label)) << label;
  EXPECT_TRUE(has_text(c, "4 models"));
  EXPECT_TRUE(has_text(c, "barrier: \u03a8 \u2192 +\u221e"));
  EXPECT_TRUE(has_text(c, "may invert"));
  EXPECT_TRUE(has_text(c, "U = V = I"));  // linear's caveat
  EXPECT_TRUE(has_text(c, "Dots: 2 triangles"));
  EXPECT_TRUE(has_text(c, "a triangle's"));
  EXPECT_TRUE(has_text(c, "det F = 0, \u03a8 finite"));
  int s1 = 0;
  for (const TextItem& t : c.texts()) s1 += t.text == "\u03c3\u2081";
  EXPECT_EQ(s1, 4);
  expect_texts_inside(c);
  // One domain for all: the invertible models' whole inverted quadrant.
  EXPECT_EQ(chart_domain(s), common_landscape_domain());
}

TEST(LandscapeChart, ALongCaptionWrapsInsideTheDrawing) {
  // One model is the narrowest chart; a scene's caption with a long name must wrap.
  LandscapeChartSpec s = spec_of({Model::NeoHookean});
  s.points = {{1.0, 1.0}};
  s.points_caption =
      "Dots: the 32 triangles of course-1-mass-spring (neo-Hookean) at step 10, "
      "t = 0.04 s, and a good many more words than fit on one line of it";
  auto canvas = landscape_chart(s, ChartFormat::Png);
  expect_texts_inside(*canvas);
  EXPECT_TRUE(has_text(*canvas, "Dots: the 32 triangles"));
}

TEST(LandscapeChart, VectorFormatsStaySmall) {
  // The heat map's equal neighbours merge into one rectangle: an SVG of the four models is
  // not a rectangle per cell.
  LandscapeChartSpec s =
      spec_of({Model::NeoHookean, Model::Linear, Model::Arap, Model::StableNeoHookean});
  auto canvas = landscape_chart(s, ChartFormat::Svg);
  const std::string svg = canvas->finish();
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_LT(svg.size(), 3u << 20);
  auto pdf = landscape_chart(s, ChartFormat::Pdf)->finish();
  EXPECT_EQ(pdf.compare(0, 5, "%PDF-"), 0);
}

}  // namespace
}  // namespace invfree
