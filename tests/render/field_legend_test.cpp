// The colourings beside det F, without GL: the colour maps' ends (app/field_colormap.h),
// the automatic scales and their round ticks and labels (app/render/field_legend.h), the
// field's summary over a frame, and a movie's widening scale (view_choices.h).
#include "app/render/field_legend.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "app/field_colormap.h"
#include "app/render/view_choices.h"

namespace invfree::render {
namespace {

void expect_color(Rgb actual, Rgb expected) {
  EXPECT_FLOAT_EQ(actual.r, expected.r);
  EXPECT_FLOAT_EQ(actual.g, expected.g);
  EXPECT_FLOAT_EQ(actual.b, expected.b);
}

std::vector<std::string> labels(const std::vector<FieldTick>& ticks) {
  std::vector<std::string> out;
  for (const FieldTick& t : ticks) out.push_back(t.label);
  return out;
}

TEST(FieldColormap, SequentialEndsAreYlOrRdsAndOutsideValuesClamp) {
  expect_color(sequential_color(0.0), {1.0f, 1.0f, 0.8f});      // pale yellow: little energy
  expect_color(sequential_color(1.0), {0.502f, 0.0f, 0.149f});  // dark red: the most
  expect_color(sequential_color(-3.0), sequential_color(0.0));
  expect_color(sequential_color(7.0), sequential_color(1.0));
  expect_color(sequential_color(std::nan("")), sequential_color(0.0));
  // Darker all the way up (the sum of the channels falls).
  double last = 4.0;
  for (int k = 0; k <= 16; ++k) {
    const Rgb c = sequential_color(k / 16.0);
    EXPECT_LT(c.r + c.g + c.b, last) << k;
    last = c.r + c.g + c.b;
  }
}

TEST(FieldColormap, StressIsDivergingAroundZeroTensionRed) {
  const FieldScale s = auto_stress_scale(403e3);
  EXPECT_EQ(s.hi, 500e3);
  EXPECT_EQ(s.lo, -500e3);
  expect_color(field_color(s, 0.0), {1.0f, 1.0f, 1.0f});
  expect_color(field_color(s, 500e3), diverging_color(1.0));    // tension: dark red
  expect_color(field_color(s, -500e3), diverging_color(-1.0));  // compression: dark blue
  expect_color(field_color(s, -9e9), diverging_color(-1.0));
  EXPECT_GT(field_color(s, 250e3).r, field_color(s, 250e3).b);
  EXPECT_GT(field_color(s, -250e3).b, field_color(s, -250e3).r);
  EXPECT_EQ(field_bar_position(s, 0.0), 0.5);
  EXPECT_EQ(field_bar_position(s, 500e3), 1.0);
  EXPECT_EQ(auto_stress_scale(0.0).hi, 1.0);  // at rest: 1 Pa, all white
}

TEST(FieldColormap, ClampedCategoriesAreDistinctAndNoneIsTheInvertedGreen) {
  expect_color(clamped_color(0), {1.0f, 1.0f, 1.0f});  // 0: Newton's Hessian is the true one
  expect_color(clamped_color(4), {0.498f, 0.0f, 0.0f});
  expect_color(clamped_color(-1), clamped_color(0));
  expect_color(clamped_color(9), clamped_color(4));
  for (int a = 0; a < kClampedCategories; ++a)
    for (int b = a + 1; b < kClampedCategories; ++b) {
      const Rgb x = clamped_color(a), y = clamped_color(b);
      EXPECT_GT(std::abs(x.r - y.r) + std::abs(x.g - y.g) + std::abs(x.b - y.b), 0.2) << a << b;
    }
  const FieldScale s = clamped_scale();
  EXPECT_EQ(field_bar_position(s, 0), 0.1);  // each category's box middle
  EXPECT_EQ(field_bar_position(s, 4), 0.9);
  // The inverted green is on no scale: a ring marks inverted triangles, not a colour.
  const auto far_from_green = [](Rgb c) {
    return std::abs(c.r - kInvertedColor.r) + std::abs(c.g - kInvertedColor.g) +
               std::abs(c.b - kInvertedColor.b) >
           0.5;
  };
  for (int k = 0; k <= 20; ++k) {
    EXPECT_TRUE(far_from_green(sequential_color(k / 20.0))) << k;
    EXPECT_TRUE(far_from_green(diverging_color(k / 10.0 - 1.0))) << k;
  }
  for (int k = 0; k < kClampedCategories; ++k) EXPECT_TRUE(far_from_green(clamped_color(k)));
}

TEST(FieldScale, NiceRoundNumbers) {
  EXPECT_EQ(nice_ceil(133e3), 200e3);
  EXPECT_EQ(nice_ceil(403e3), 500e3);
  EXPECT_EQ(nice_ceil(1000.0), 1000.0);
  EXPECT_EQ(nice_ceil(0.03), 0.05);
  EXPECT_EQ(nice_floor(4610.0), 2000.0);
  EXPECT_EQ(nice_floor(1610.0), 1000.0);
  EXPECT_EQ(nice_floor(500.0), 500.0);
  EXPECT_EQ(nice_floor(9.99), 5.0);
}

TEST(FieldScale, PsiIsLogFromTheDataAtMostFourDecades) {
  // compress n_seg 8 squashed (step 280): 4.61 kPa .. 133 kPa.
  FieldScale s = auto_psi_scale(4.61e3, 133e3);
  EXPECT_EQ(s.lo, 2e3);
  EXPECT_EQ(s.hi, 200e3);
  EXPECT_TRUE(s.automatic);
  // Log: each decade the same length of the bar.
  EXPECT_NEAR(field_bar_position(s, 20e3), 0.5, 1e-12);
  EXPECT_NEAR(field_bar_position(s, 2e3), 0.0, 1e-12);
  EXPECT_EQ(field_bar_position(s, 1.0), 0.0);  // below the scale: its bottom colour
  EXPECT_EQ(field_bar_position(s, 0.0), 0.0);  // no energy
  EXPECT_EQ(field_bar_position(s, 1e9), 1.0);
  // First contact (step 32): 0.007 Pa .. 1.28 kPa, 5 decades: the bottom 4 below the top.
  s = auto_psi_scale(0.00687, 1280.0);
  EXPECT_EQ(s.hi, 2000.0);
  EXPECT_NEAR(s.lo, 0.2, 1e-12);
  // Nearly uniform (step 150): 1.61 .. 2.37 kPa gets 1..5 kPa, not a whole decade.
  s = auto_psi_scale(1.61e3, 2.37e3);
  EXPECT_EQ(s.lo, 1e3);
  EXPECT_EQ(s.hi, 5e3);
  // One value: a step below it.
  s = auto_psi_scale(1e3, 1e3);
  EXPECT_EQ(s.hi, 1e3);
  EXPECT_EQ(s.lo, 500.0);
  // At rest: 1..10 Pa.
  s = auto_psi_scale(0.0, 0.0);
  EXPECT_EQ(s.lo, 1.0);
  EXPECT_EQ(s.hi, 10.0);
  // Psi = +inf (a barrier model at J <= 0) is left out of the stats, coloured as the top.
  const FieldStats st =
      field_stats(TriangleField::Psi, {0.0, 5.0, std::numeric_limits<double>::infinity(), 300.0});
  EXPECT_EQ(st.count, 3);
  EXPECT_EQ(st.min, 0.0);
  EXPECT_EQ(st.max, 300.0);
  EXPECT_EQ(st.min_positive, 5.0);
  expect_color(field_color(auto_field_scale(TriangleField::Psi, st),
                           std::numeric_limits<double>::infinity()),
               sequential_color(1.0));
}

TEST(FieldLegend, TicksAreRoundNumbers) {
  // Psi: decades, each label with its own prefix.
  FieldScale psi = auto_psi_scale(4.61e3, 133e3);
  EXPECT_EQ(labels(field_bar_ticks(psi)),
            (std::vector<std::string>{"≤ 2 kPa", "10 kPa", "100 kPa", "200 kPa"}));
  // Under two decades: 1, 2, 5 steps between the ends.
  psi = auto_psi_scale(1.61e3, 2.37e3);
  EXPECT_EQ(labels(field_bar_ticks(psi)), (std::vector<std::string>{"≤ 1 kPa", "2 kPa", "5 kPa"}));
  // Four decades (a decade closer to the top than 12% of the bar is left out).
  psi = auto_psi_scale(0.00687, 1280.0);
  EXPECT_EQ(labels(field_bar_ticks(psi)),
            (std::vector<std::string>{"≤ 200 mPa", "1 Pa", "10 Pa", "100 Pa", "2 kPa"}));
  for (const FieldScale& s : {psi, auto_stress_scale(7e6), clamped_scale()}) {
    const auto ticks = field_bar_ticks(s);
    for (size_t k = 1; k < ticks.size(); ++k) EXPECT_GT(ticks[k].position, ticks[k - 1].position);
    EXPECT_GE(ticks.front().position, 0.0);
    EXPECT_LE(ticks.back().position, 1.0);
  }
  const FieldScale stress = auto_stress_scale(403e3);
  EXPECT_EQ(labels(field_bar_ticks(stress)),
            (std::vector<std::string>{"−500", "−250", "0", "250", "500"}));
  EXPECT_EQ(field_unit(auto_stress_scale(7e6)).name, "MPa");
  EXPECT_EQ(labels(field_bar_ticks(auto_stress_scale(7e6))),
            (std::vector<std::string>{"−10", "−5", "0", "5", "10"}));
  EXPECT_EQ(field_unit(auto_stress_scale(0.3)).name, "Pa");
  EXPECT_EQ(labels(field_bar_ticks(clamped_scale())),
            (std::vector<std::string>{"0", "1", "2", "3", "4"}));
  EXPECT_EQ(format_in_unit(-89.3e3, {1e3, "kPa"}), "−89.3");
  EXPECT_EQ(format_in_unit(133.4e3, {1e3, "kPa"}), "133");
  EXPECT_EQ(format_in_unit(0.0, {1e3, "kPa"}), "0");
  EXPECT_EQ(format_round_si(2.5e6, "Pa"), "2.5 MPa");
  EXPECT_EQ(format_round_si(-20e3, "Pa"), "−20 kPa");
  EXPECT_EQ(format_round_si(999.7, "Pa"), "1 kPa");
  EXPECT_EQ(format_round_si(0.0, "Pa"), "0");
}

TEST(FieldLegend, WordsNameTheFieldItsUnitAndTheAutoScale) {
  const FieldLegendWords psi = field_legend_words(auto_psi_scale(4.61e3, 133e3));
  EXPECT_EQ(psi.title, "Ψ (auto scale)");
  EXPECT_NE(psi.subtitle.find("energy density, Pa = J/m³"), std::string::npos);
  EXPECT_NE(psi.subtitle.find("log"), std::string::npos);
  const FieldLegendWords stress = field_legend_words(auto_stress_scale(403e3));
  EXPECT_EQ(stress.title, "stress (auto scale)");
  EXPECT_NE(stress.subtitle.find("largest |principal Cauchy stress|, signed"), std::string::npos);
  EXPECT_NE(stress.subtitle.find("kPa"), std::string::npos);
  EXPECT_EQ(stress.top_note, "tension");
  EXPECT_EQ(stress.bottom_note, "compression");
  FieldScale fixed = auto_stress_scale(1.0);
  fixed.automatic = false;
  EXPECT_EQ(field_legend_words(fixed).title, "stress");
  EXPECT_EQ(field_legend_words(clamped_scale()).title, "clamped");
  // Wrapping to the panel: by words, a too-long word on a line of its own.
  const auto width = [](const std::string& s) { return double(s.size()); };
  EXPECT_EQ(wrap_words("largest |principal Cauchy stress|, signed", 20, width),
            (std::vector<std::string>{"largest |principal", "Cauchy stress|,", "signed"}));
  EXPECT_EQ(wrap_words("a verylongword b", 5, width),
            (std::vector<std::string>{"a", "verylongword", "b"}));
  EXPECT_EQ(wrap_words("energy density\nlog scale", 40, width),
            (std::vector<std::string>{"energy density", "log scale"}));
}

TEST(FieldLegend, ClampedStatsCountEachCategory) {
  const FieldStats s = field_stats(TriangleField::Clamped, {0, 1, 1, 4, 2, 0, 0});
  EXPECT_EQ(s.category_counts[0], 3);
  EXPECT_EQ(s.category_counts[1], 2);
  EXPECT_EQ(s.category_counts[2], 1);
  EXPECT_EQ(s.category_counts[3], 0);
  EXPECT_EQ(s.category_counts[4], 1);
}

TEST(FieldLegend, AMoviesScaleOnlyWidensUnlessPerFrame) {
  FrameState f;
  f.color_by = TriangleField::Stress;
  ColorRangeTracker run{ColorRangeMode::Run}, frame{ColorRangeMode::Frame},
      fixed{ColorRangeMode::Fixed};
  DrawOptions o;
  f.field = {-40e3, 10e3};
  run.apply_field(f, &o);
  ASSERT_TRUE(o.field_scale);
  EXPECT_EQ(o.field_scale->hi, 50e3);
  f.field = {-4e3, 1e3};
  run.apply_field(f, &o);
  EXPECT_EQ(o.field_scale->hi, 50e3);  // the widest so far
  fixed.apply_field(f, &o);
  EXPECT_EQ(o.field_scale->hi, 5e3);  // fixed: widest so far too (its first frame here)
  frame.apply_field(f, &o);
  EXPECT_FALSE(o.field_scale);  // the renderer scales each frame by itself
  f.color_by = TriangleField::DetF;
  run.apply_field(f, &o);
  EXPECT_FALSE(o.field_scale);  // det F's range is apply's
}

TEST(FieldLegend, FramesShownTogetherShareOneScale) {
  // render --compare's two views: one scale from both frames' values, in every mode.
  FrameState a, b;
  a.color_by = b.color_by = TriangleField::Psi;
  a.field = {3e3, 190e3};  // alone: 2 kPa..200 kPa
  b.field = {40, 9e3};     // alone: 20 Pa..10 kPa
  for (const ColorRangeMode mode :
       {ColorRangeMode::Frame, ColorRangeMode::Run, ColorRangeMode::Fixed}) {
    ColorRangeTracker tracker{mode};
    DrawOptions o;
    tracker.apply_field({&a, &b}, &o);
    ASSERT_TRUE(o.field_scale) << color_range_mode_name(mode);
    EXPECT_DOUBLE_EQ(o.field_scale->lo, 20.0) << color_range_mode_name(mode);
    EXPECT_DOUBLE_EQ(o.field_scale->hi, 200e3) << color_range_mode_name(mode);
    tracker.apply_field({&b, &a}, &o);  // either order
    EXPECT_DOUBLE_EQ(o.field_scale->lo, 20.0) << color_range_mode_name(mode);
    EXPECT_DOUBLE_EQ(o.field_scale->hi, 200e3) << color_range_mode_name(mode);
  }
  const FieldStats both = combine_field_stats(field_stats(TriangleField::Stress, {-40e3, 1e3}),
                                              field_stats(TriangleField::Stress, {2e3, 7e3}));
  EXPECT_EQ(both.min, -40e3);
  EXPECT_EQ(both.max, 7e3);
  EXPECT_EQ(both.min_positive, 1e3);
  EXPECT_EQ(both.max_abs, 40e3);
  EXPECT_EQ(both.count, 4);
  EXPECT_EQ(combine_field_stats(FieldStats{}, both).max, 7e3);  // no values: adds nothing
}

}  // namespace
}  // namespace invfree::render
