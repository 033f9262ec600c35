// The renderer's pieces that need no GL: the overlay's words and numbers, the colour
// bar's ticks, the fixed camera, UTF-8 decoding, the frame writer's PNG encoding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/body_extent.h"
#include "app/colormap.h"
#include "app/render/camera.h"
#include "app/render/frame_text.h"
#include "app/render/frame_writer.h"
#include "app/render/shader_sources.h"
#include "app/render/text_atlas.h"
#include "app/render/view_choices.h"
#include "scene/scene.h"
#include "scene_io/builtin_scenes.h"
#include "tests/render/image_compare.h"

namespace invfree::render {
namespace {

TEST(ColorRange, AutoRangeIsTheSmallestRoundRangeHoldingTheData) {
  // Symmetric in log det F around 1: 1/range..range holds [lo, hi].
  EXPECT_EQ(auto_det_f_range(1.0, 1.0), 1.01);
  EXPECT_EQ(auto_det_f_range(0.99, 1.004), 1.02);  // 1/0.99 = 1.0101 > 1.01
  EXPECT_EQ(auto_det_f_range(0.84, 1.04), 1.2);    // compress's first second
  EXPECT_EQ(auto_det_f_range(0.5, 1.1), 2.0);
  EXPECT_EQ(auto_det_f_range(0.2, 1.0), 8.0);
  EXPECT_EQ(auto_det_f_range(-0.3, 1.3), 1.5);  // inverted (green anyway) is left out
  EXPECT_EQ(auto_det_f_range(1e-9, 1.0), 1024.0);
  for (double lo : {0.3, 0.7, 0.95, 0.999})
    for (double hi : {1.0, 1.01, 1.3, 3.0}) {
      const double r = auto_det_f_range(lo, hi);
      EXPECT_LE(1.0 / r, lo * (1 + 1e-12));
      EXPECT_GE(r, hi * (1 - 1e-12));
    }
  // A run that reaches det F 0.001 (range 1024): at most nine ticks, short labels (21
  // overlapping ones, "0.000976562" the longest, before).
  const auto wide = color_bar_ticks(1024.0);
  EXPECT_LE(wide.size(), 9u);
  EXPECT_TRUE(
      std::any_of(wide.begin(), wide.end(), [](const ColorBarTick& t) { return t.value == 1.0; }));
  for (const auto& t : wide) EXPECT_LE(t.label.size(), 7u) << t.label;  // "0.00195"
  // A small range's bar: its ends and 1, labelled.
  const auto ticks = color_bar_ticks(1.05);
  ASSERT_EQ(ticks.size(), 3u);
  EXPECT_EQ(ticks[0].label, "0.952");
  EXPECT_EQ(ticks[1].label, "1");
  EXPECT_EQ(ticks[2].label, "1.05");
  EXPECT_EQ(ticks[0].position, -1.0);
  EXPECT_EQ(ticks[2].position, 1.0);
}

TEST(ColorRange, RunModeOnlyWidensFrameModeFollowsTheFrame) {
  ColorRangeTracker run{ColorRangeMode::Run}, frame{ColorRangeMode::Frame},
      fixed{ColorRangeMode::Fixed};
  DrawOptions o;
  run.apply(0.8, 1.0, &o);
  EXPECT_EQ(o.color_range, 1.5);
  EXPECT_TRUE(o.color_range_auto);
  run.apply(0.99, 1.0, &o);
  EXPECT_EQ(o.color_range, 1.5);  // the run so far
  frame.apply(0.8, 1.0, &o);
  frame.apply(0.99, 1.0, &o);
  EXPECT_EQ(o.color_range, 1.02);
  fixed.apply(0.99, 1.0, &o);
  EXPECT_EQ(o.color_range, kDetFRange);
  EXPECT_FALSE(o.color_range_auto);
  EXPECT_EQ(parse_color_range_mode("run"), ColorRangeMode::Run);
  EXPECT_FALSE(parse_color_range_mode("auto"));
}

TEST(FollowCamera, FramesTheBodyAndNeverJumps) {
  // A square falling 2 m and squashing: every node stays in the plot, and the camera's
  // scale and centre change by a bounded fraction per frame.
  const PixelRect plot{0, 0, 990, 720};
  FollowCamera follow;
  FrameState st;
  st.scene.side = 1.0;
  Camera last;
  for (int f = 0; f < 200; ++f) {
    const double drop = std::min(2.0, 0.02 * f), squash = f < 100 ? 1.0 : 1.0 - 0.004 * (f - 100);
    st.x.resize(8);
    const double hw = 0.5 / squash, hh = 0.5 * squash;
    st.x << -hw, -hh - drop, hw, -hh - drop, hw, hh - drop, -hw, hh - drop;
    const Camera c = follow.next(st, plot);
    for (int i = 0; i < 4; ++i) {
      const Vec2 p = c.to_pixel(st.x.segment<2>(2 * i));
      EXPECT_GE(p.x(), plot.x);
      EXPECT_LE(p.x(), plot.x + plot.w);
      EXPECT_GE(p.y(), plot.y);
      EXPECT_LE(p.y(), plot.y + plot.h);
    }
    if (f > 0) {
      EXPECT_LT(std::abs(c.pixels_per_metre / last.pixels_per_metre - 1.0), 0.1) << f;
      EXPECT_LT((c.origin - last.origin).norm(), 60.0) << f;
    }
    last = c;
  }
}

TEST(FrameText, SiPrefixesWithThreeSignificantDigits) {
  const Lame l = lame_from_young_poisson(1e5, 0.4);  // the demo's: 35714 and 142857 Pa
  EXPECT_EQ(format_si(l.mu, "Pa"), "35.7 kPa");
  EXPECT_EQ(format_si(l.lambda, "Pa"), "143 kPa");
  EXPECT_EQ(format_si(999.6, "Pa"), "1.00 kPa");
  EXPECT_EQ(format_si(850.0, "Pa"), "850 Pa");
  EXPECT_EQ(format_si(2.5e6, "Pa"), "2.50 MPa");
  EXPECT_EQ(format_si(0.0, "Pa"), "0 Pa");
}

TEST(FrameText, TimeHasTheDecimalsOfTheStep) {
  EXPECT_EQ(format_time(1.23, 0.01), "t = 1.23 s");
  EXPECT_EQ(format_time(0.5, 0.001), "t = 0.500 s");
  EXPECT_EQ(format_time(2.0, 0.1), "t = 2.00 s");
}

TEST(FrameText, ColorBarTicksArePowersOfTwoOnTheColormapScale) {
  const auto ticks = color_bar_ticks(kDetFRange);
  ASSERT_EQ(ticks.size(), 5u);  // 1/4 .. 4
  const char* labels[] = {"0.25", "0.5", "1", "2", "4"};
  for (size_t i = 0; i < ticks.size(); ++i) {
    EXPECT_EQ(ticks[i].label, labels[i]);
    EXPECT_DOUBLE_EQ(ticks[i].position, det_f_scale_position(ticks[i].value));
  }
  EXPECT_DOUBLE_EQ(ticks.front().position, -1.0);
  EXPECT_DOUBLE_EQ(ticks[2].position, 0.0);
  EXPECT_LE(color_bar_ticks(1024.0).size(), 11u);  // every other power when many
}

TEST(Camera, FixedPerSceneAndHoldsPlanesAndSquashedSquare) {
  const SceneDef s = *load_builtin_scene("compress").scene;
  const WorldBox box = scene_world_box(s);
  EXPECT_LT(box.y0, s.ground_y);
  EXPECT_GT(box.y1, s.ceiling_y);
  // Squashed to the ceiling's stop gap at constant area, the square is side^2/gap wide.
  const double squashed = s.side * s.side / (s.ceiling_stop - s.ground_y);
  EXPECT_GE(box.x1 - box.x0, squashed);
  // Depends on the definition only: the same box whatever the state.
  SceneDef moved = s;
  EXPECT_EQ(scene_world_box(moved).x0, box.x0);
  const FrameLayout l = frame_layout(1280, 720);
  const Camera c = scene_camera(s, l);
  for (const Vec2& corner : {Vec2(box.x0, box.y0), Vec2(box.x1, box.y1)}) {
    const Vec2 p = c.to_pixel(corner);
    EXPECT_GE(p.x(), l.plot.x - 1e-9);
    EXPECT_LE(p.x(), l.plot.x + l.plot.w + 1e-9);
    EXPECT_GE(p.y(), l.plot.y - 1e-9);
    EXPECT_LE(p.y(), l.plot.y + l.plot.h + 1e-9);
    EXPECT_LT((c.to_world(p) - corner).norm(), 1e-12);
  }
  EXPECT_NEAR(c.to_pixel(Vec2(0, 0)).x(), l.plot.x + 0.5 * l.plot.w, 1e-9);  // centred
}

// Each shape scene's camera holds its body's rest bounding box with room around it, the
// planes it has, and (plate-hole: no ground, no ceiling) a margin on every side.
TEST(Camera, FramesEveryShapeScenesBodyWithAMargin) {
  for (const char* name : {"ring", "c-shape", "plate-hole", "bunny"}) {
    SCOPED_TRACE(name);
    const SceneLoad load = load_builtin_scene(name);
    ASSERT_TRUE(load.scene) << load.error;
    const SceneDef& s = *load.scene;
    const BodyExtent b = body_rest_extent(s, 0);
    ASSERT_GT(b.width, 0.0);
    const WorldBox box = scene_world_box(s);
    const double margin = 0.1 * b.size();
    EXPECT_LE(box.x0, b.x0 - margin);
    EXPECT_GE(box.x1, b.x1 + margin);
    EXPECT_LE(box.y0, b.y0 - margin);
    EXPECT_GE(box.y1, b.y1 + margin);
    if (s.has_ground) {
      EXPECT_LT(box.y0, s.ground_y);
    }
    if (s.has_ceiling) {
      EXPECT_GT(box.y1, s.ceiling_y);
    }
  }
  // The 2 m x 1 m plate: its own extent, not the [mesh] side's 1 m square.
  const SceneDef plate = *load_builtin_scene("plate-hole").scene;
  const BodyExtent e = body_rest_extent(plate, 0);
  EXPECT_NEAR(e.width, 2.0, 0.02);
  EXPECT_NEAR(e.height, 1.0, 0.02);
  EXPECT_NEAR(scene_length_scale(plate), 2.0, 0.02);
}

// A square's extent is its offset +- side / 2, exactly as the camera computed it before
// shapes (the goldens depend on it), and the length scale of a square scene is its side.
TEST(Camera, ASquaresExtentIsItsSideExactly) {
  SceneDef s = *load_builtin_scene("stack").scene;
  for (int k = 0; k < body_count(s); ++k) {
    const PlacedBody p = placed_body(s, k);
    const BodyExtent b = body_rest_extent(s, k);
    EXPECT_EQ(b.x0, p.offset.x() - 0.5 * p.side);
    EXPECT_EQ(b.x1, p.offset.x() + 0.5 * p.side);
    EXPECT_EQ(b.y0, p.offset.y() - 0.5 * p.side);
    EXPECT_EQ(b.y1, p.offset.y() + 0.5 * p.side);
    EXPECT_EQ(b.width, p.side);
    EXPECT_EQ(b.height, p.side);
  }
  s.side = 0.7;
  EXPECT_EQ(scene_length_scale(s), 0.7);
}

TEST(Camera, PanelOnTheRightOrNone) {
  const FrameLayout with = frame_layout(1280, 720), without = frame_layout(1280, 720, false);
  EXPECT_DOUBLE_EQ(with.plot.w + with.panel.w, 1280.0);
  EXPECT_GT(with.panel.w, 0.0);
  EXPECT_DOUBLE_EQ(without.plot.w, 1280.0);
  EXPECT_DOUBLE_EQ(with.scale, 1.0);
  EXPECT_DOUBLE_EQ(frame_layout(640, 360).scale, 0.5);
}

TEST(TextAtlas, DecodesUtf8AndReplacesBrokenBytes) {
  EXPECT_EQ(decode_utf8("μ = λ ≤ 1"), U"μ = λ ≤ 1");
  EXPECT_EQ(decode_utf8("a\xff"
                        "b"),
            U"a?b");
  EXPECT_EQ(decode_utf8("\xce"), U"?");  // truncated sequence
}

TEST(TextAtlas, WiderTextAndKnownGlyphs) {
  TextAtlas atlas;
  atlas.build({20.0});
  EXPECT_GT(atlas.text_width("det F = 0.425", 0), atlas.text_width("det F", 0));
  std::vector<GlyphQuad> quads;
  atlas.layout("μλ≤▶", 0, 10.0, 30.0, &quads);
  ASSERT_EQ(quads.size(), 4u);
  for (const GlyphQuad& q : quads) {  // whole pixels, inside the atlas
    EXPECT_EQ(q.x0, std::round(q.x0));
    EXPECT_EQ(q.y0, std::round(q.y0));
    EXPECT_LE(q.u1, atlas.width());
    EXPECT_LE(q.v1, atlas.height());
  }
}

TEST(FrameWriter, PngRoundTripFlipsToTopRowFirst) {
  const int w = 3, h = 2;
  std::vector<std::uint8_t> rgba(w * h * 4);
  for (int i = 0; i < w * h * 4; ++i) rgba[i] = static_cast<std::uint8_t>(i * 7);
  const std::string path = ::testing::TempDir() + "/roundtrip.png";
  ASSERT_EQ(write_png_file(path, rgba.data(), w, h, 1), "");
  test::RgbImage back;
  ASSERT_TRUE(test::load_png(path, &back));
  ASSERT_EQ(back.width, w);
  ASSERT_EQ(back.height, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)  // PNG row y is GL row h-1-y
        EXPECT_EQ(back.rgb[(y * w + x) * 3 + c], rgba[((h - 1 - y) * w + x) * 4 + c]);
}

// The web build's shaders: the same files with the version line switched for WebGL 2.
TEST(ShaderSources, VersionLineSwitchedForOpenGlEsOnly) {
  for (const char* source : {shader_sources().shape_vertex, shader_sources().shape_fragment,
                             shader_sources().fill_fragment, shader_sources().text_vertex,
                             shader_sources().text_fragment}) {
    EXPECT_EQ(glsl_for_context(source, false), source);
    const std::string es = glsl_for_context(source, true);
    EXPECT_EQ(es.rfind("#version 300 es\nprecision highp float;\n", 0), 0u) << es;
    EXPECT_EQ(es.find("#version 330"), std::string::npos) << es;
    // Everything else is kept: the ES text is the desktop text less its version line.
    EXPECT_EQ(es.size(), std::string(source).size() - std::string("#version 330 core\n").size() +
                             std::string("#version 300 es\nprecision highp float;\nprecision "
                                         "highp int;\n")
                                 .size());
  }
}

TEST(ImageCompare, ToleranceRule) {
  test::RgbImage a{100, 100, std::vector<std::uint8_t>(100 * 100 * 3, 128)}, b = a;
  EXPECT_TRUE(test::compare_images(a, b).matches());
  for (int p = 0; p < 10; ++p) b.rgb[p * 3] = 128 + 40;  // 10 of 10000 pixels: 0.1%, allowed
  EXPECT_TRUE(test::compare_images(a, b).matches());
  b.rgb[10 * 3 + 1] = 128 - 6;  // an 11th differing by 6/255 in one channel: over
  EXPECT_EQ(test::compare_images(a, b).differing, 11);
  EXPECT_FALSE(test::compare_images(a, b).matches());
  b.rgb[10 * 3 + 1] = 128 - 5;  // 5/255 is within the threshold
  EXPECT_TRUE(test::compare_images(a, b).matches());
  test::RgbImage small{10, 10, std::vector<std::uint8_t>(300, 128)};
  EXPECT_FALSE(test::compare_images(a, small).matches());
}

}  // namespace
}  // namespace invfree::render
