// `invfree render --compare A,B` end to end (issue 32 item 7): two methods on one scene in
// lockstep, one frame with the two views side by side. Read from the frames' pixels: each
// view's heading, its bodies, the agreement of two methods that must agree (the lecture's
// diagonal projection and the 6x6 clamp, early on), a failing side's mark while the other
// side goes on, one Psi and stress colour scale for both views; and the command line's
// errors. Runs with DISPLAY unset.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "app/render/camera.h"
#include "tests/render/image_compare.h"
#include "tests/run_command.h"
#include "tests/test_paths.h"

namespace {

namespace fs = std::filesystem;

using invfree::render::FrameLayout;
using invfree::render::PixelRect;
using invfree::test::CommandResult;
using invfree::test::RgbImage;

CommandResult run(const std::string& args) {
  return invfree::test::run_command(::invfree::test::exe_path(), args, true, "");
}

std::string fresh_dir(const std::string& name) {
  const std::string dir =
      ::testing::TempDir() + "/render_compare_" + name + "_" + std::to_string(::getpid());
  fs::remove_all(dir);
  return dir;
}

RgbImage frame(const std::string& dir, int i) {
  char name[32];
  std::snprintf(name, sizeof name, "/frame_%06d.png", i);
  RgbImage image;
  EXPECT_TRUE(invfree::test::load_png(dir + name, &image)) << dir << name;
  return image;
}

// The rectangle `r` of `image` shifted right by `dx` pixels, as an image of its own.
RgbImage crop(const RgbImage& image, const PixelRect& r, int dx) {
  RgbImage out;
  out.width = static_cast<int>(r.w);
  out.height = static_cast<int>(r.h);
  for (int y = static_cast<int>(r.y); y < static_cast<int>(r.y + r.h); ++y)
    for (int x = static_cast<int>(r.x); x < static_cast<int>(r.x + r.w); ++x)
      for (int c = 0; c < 3; ++c)
        out.rgb.push_back(image.rgb[3 * (size_t(y) * image.width + x + dx) + c]);
  return out;
}

// Pixels of `image` for which `test(r, g, b)` holds.
template <class Test>
long count(const RgbImage& image, Test test) {
  long n = 0;
  for (size_t i = 0; i + 2 < image.rgb.size(); i += 3)
    n += test(image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]) ? 1 : 0;
  return n;
}
bool failure_red(int r, int g, int b) {  // the failure mark's ink, (0.80, 0.04, 0.06)
  return r > 180 && g < 40 && b < 40;
}
bool ink(int r, int g, int b) {  // the heading's dark text
  return r < 110 && g < 110 && b < 110;
}
bool near_white(int r, int g, int b) {  // det F = 1 (the plot's background is 244..247)
  return r >= 251 && g >= 251 && b >= 251;
}

// One view's layout at a frame of width x height (two views of half the width).
FrameLayout view_layout(int width, int height) {
  return invfree::render::frame_layout(width / 2, height);
}

TEST(RenderCompare, MethodListErrorsAreOneLineAndNameTheMethods) {
  const std::string dir = fresh_dir("errors");
  for (const std::string list :
       {"lecture", "lecture,lecture", "lecture,bogus", "a,b,c", "lecture,"}) {
    const CommandResult r =
        run("render --scene compress --frames 2 --compare " + list + " --out " + dir);
    EXPECT_EQ(r.code, 2) << list << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << list << ": " << r.err;
    EXPECT_NE(r.err.find("--compare"), std::string::npos) << r.err;
    // The valid names are listed.
    EXPECT_NE(r.err.find("lecture, plain-line-search, full-eigen-clamp, no-projection"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir + "/frame_000000.png")) << list;
  }
  EXPECT_NE(run("render --compare lecture,lecture --out " + dir).err.find("'lecture' twice"),
            std::string::npos);
  EXPECT_NE(run("render --compare lecture,bogus --out " + dir).err.find("unknown method 'bogus'"),
            std::string::npos);
  EXPECT_NE(run("render --compare a,b,c --out " + dir).err.find("got 3"), std::string::npos);
  // Two views of half the width: an odd width is refused.
  const CommandResult odd =
      run("render --compare lecture,no-projection --size 961x540 --out " + dir);
  EXPECT_EQ(odd.code, 2);
  EXPECT_NE(odd.err.find("even width"), std::string::npos) << odd.err;
  // A method that does not apply to the scene (no self-contact: nothing to take CCD from).
  const CommandResult na = run(
      "render --scene compress --set self_contact.enabled=false --compare lecture,no-ccd --out " +
      dir);
  EXPECT_EQ(na.code, 2);
  EXPECT_NE(na.err.find("--compare: no-ccd: "), std::string::npos) << na.err;
}

TEST(RenderCompare, TwoMethodsThatMustAgreeDrawTheSameViews) {
  // The lecture's diagonal-space projection and the 6x6 clamp give the same steps while
  // nothing is compressed: frame 0 is the same state in both views, and the early frames
  // agree; only the headings (and the panels' method lines) differ.
  const std::string dir = fresh_dir("agree");
  const CommandResult r =
      run("render --scene compress --compare lecture,full-eigen-clamp --frames 4 --size 960x540 "
          "--out " +
          dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("compress: 4 frames 960x540"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lecture (left) beside full-eigen-clamp (right)"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("render: left lecture: 3 steps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("render: right full-eigen-clamp: 3 steps"), std::string::npos) << r.out;
  const FrameLayout L = view_layout(960, 540);
  const double band = invfree::render::title_band_height(L);
  const PixelRect world = invfree::render::below_title(L);
  const PixelRect heading{L.plot.x, L.plot.y, L.plot.w, band};
  const int half = L.width;
  for (const int i : {0, 3}) {
    const RgbImage image = frame(dir, i);
    ASSERT_EQ(image.width, 960);
    ASSERT_EQ(image.height, 540);
    const RgbImage left = crop(image, world, 0), right = crop(image, world, half);
    // Each view shows the body (white-ish triangles at det F near 1), the same size.
    const long left_body = count(left, near_white), right_body = count(right, near_white);
    EXPECT_GT(left_body, 2000) << "frame " << i;
    EXPECT_NEAR(double(left_body), double(right_body), 0.01 * left_body) << "frame " << i;
    const invfree::test::ImageDiff d = invfree::test::compare_images(left, right, i == 0 ? 0 : 5);
    if (i == 0)
      EXPECT_EQ(d.differing, 0) << "frame 0: the same state, camera and colours";
    else
      EXPECT_TRUE(d.matches()) << "frame " << i << ": " << d.differing << " of " << d.pixels;
    // Each heading has its words, and they differ (the methods' names).
    const RgbImage left_title = crop(image, heading, 0), right_title = crop(image, heading, half);
    EXPECT_GT(count(left_title, ink), 100);
    EXPECT_GT(count(right_title, ink), 100);
    EXPECT_FALSE(invfree::test::compare_images(left_title, right_title).matches(0.0));
    EXPECT_EQ(count(image, failure_red), 0);
  }
}

TEST(RenderCompare, AFailingSideIsMarkedWhileTheOtherGoesOn) {
  // stress-soft (E = 1e3 Pa): without the inversion filter the run fails within half a
  // second (invfree stability's table), the lecture's goes on. A fixed camera and colour
  // scale, so that the failed side's view stays exactly as it was.
  const std::string scene =
      std::string(invfree::test::source_dir()) + "/assets/scenes/stress-soft.toml";
  const std::string dir = fresh_dir("fails");
  const int frames = 60;
  const CommandResult r =
      run("render --scene " + scene + " --compare lecture,no-inversion-filter --frames " +
          std::to_string(frames) +
          " --size 960x540 --min-n-seg 0 --camera fixed --color-range fixed --out " + dir);
  ASSERT_EQ(r.code, 0) << r.err << r.out;  // the failure is what the frames show
  EXPECT_NE(r.out.find("render: left lecture: " + std::to_string(frames - 1) + " steps"),
            std::string::npos)
      << r.out;
  const size_t right = r.out.find("render: right no-inversion-filter: ");
  ASSERT_NE(right, std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAILED at step", right), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("FAILED"), r.out.find("FAILED", right)) << "only the right side failed";
  const FrameLayout L = view_layout(960, 540);
  const int half = L.width;
  const RgbImage last = frame(dir, frames - 1), before = frame(dir, frames - 5);
  const PixelRect plot = L.plot;
  // The right view is marked (its border and banner), the left one not.
  EXPECT_GT(count(crop(last, plot, half), failure_red), 2000);
  EXPECT_EQ(count(crop(last, plot, 0), failure_red), 0);
  // The failed side keeps its last good state; the lecture's side still moves.
  const PixelRect view{0, 0, double(half), double(L.height)};
  EXPECT_EQ(
      invfree::test::compare_images(crop(last, view, half), crop(before, view, half), 0).differing,
      0);
  EXPECT_GT(invfree::test::compare_images(crop(last, view, 0), crop(before, view, 0), 0).differing,
            0);
}

// The colour bar of the view whose panel starts at x = `panel_x` (the frame's whole height):
// the columns and rows of the panel where most pixels are strongly coloured (the panel's
// text is grey or black, the inverted triangles' swatch small).
struct BarBox {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
};
BarBox find_colour_bar(const RgbImage& image, int panel_x, int panel_w) {
  const auto coloured = [&](int x, int y) {
    const std::uint8_t* p = &image.rgb[3 * (size_t(y) * image.width + x)];
    return std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) > 40;
  };
  BarBox b{-1, -1, image.height, 0};
  for (int x = panel_x; x < panel_x + panel_w; ++x) {
    int n = 0, top = image.height, bottom = 0;
    for (int y = 0; y < image.height; ++y)
      if (coloured(x, y)) ++n, top = std::min(top, y), bottom = std::max(bottom, y + 1);
    if (n < image.height / 4) continue;
    if (b.x0 < 0) b.x0 = x;
    b.x1 = x + 1;
    b.y0 = std::min(b.y0, top);
    b.y1 = std::max(b.y1, bottom);
  }
  return b;
}

TEST(RenderCompare, PsiAndStressHaveOneScaleForBothViews) {
  // Each side stops where its method fails and keeps its last state while the lecture's
  // squash goes on, so the two views' values differ: stress-h0.1's Psi beside plain Newton
  // (stalls at step 24; at frame 25 the lecture's largest Psi is 102 kPa, plain Newton's
  // 72 kPa: a view scaled alone tops at 200 and 100 kPa), stress-soft's stress beside
  // backtracking alone (fails at step 34; by frame 39 17 kPa against 9.6 kPa: +-20 and
  // +-10 kPa). Each view has its own panel and bar; with one scale for both, the bars,
  // their ticks and the ticks' labels are the same pixels in both views (the markers at
  // each view's min and max differ: they are left and right of what is compared). With
  // --color-range frame the scale of each frame is chosen from both views' values in it,
  // with run from both over the frames so far.
  const std::string scenes = std::string(invfree::test::source_dir()) + "/assets/scenes/";
  const struct {
    const char *scene, *methods, *field, *range;
    int frames;
  } cases[] = {{"stress-h0.1", "lecture,no-projection", "psi", "frame", 26},
               {"stress-h0.1", "lecture,no-projection", "psi", "run", 26},
               {"stress-soft", "lecture,no-inversion-filter", "stress", "frame", 40}};
  const FrameLayout L = view_layout(960, 540);
  const int half = L.width, panel_x = int(L.panel.x), panel_w = int(L.panel.w);
  for (const auto& c : cases) {
    const std::string what = std::string(c.scene) + " " + c.field + " --color-range " + c.range;
    const std::string dir = fresh_dir(std::string("scale_") + c.field + "_" + c.range);
    const CommandResult r =
        run("render --scene " + scenes + c.scene + ".toml --compare " + c.methods + " --frames " +
            std::to_string(c.frames) + " --size 960x540 --color-by " + c.field + " --color-range " +
            c.range + " --out " + dir);
    ASSERT_EQ(r.code, 0) << what << ": " << r.err << r.out;
    ASSERT_NE(r.out.find("FAILED at step"), std::string::npos) << what << ": " << r.out;
    int bars_differ = 0;
    for (int i = 0; i < c.frames; ++i) {
      const RgbImage image = frame(dir, i);
      const BarBox left = find_colour_bar(image, panel_x, panel_w),
                   right = find_colour_bar(image, half + panel_x, panel_w);
      const std::string where = what + ", frame " + std::to_string(i);
      ASSERT_GE(left.x1 - left.x0, 5) << where << ": no colour bar in the left panel";
      ASSERT_EQ(right.x0 - half, left.x0) << where;
      ASSERT_EQ(right.x1 - half, left.x1) << where;
      ASSERT_EQ(right.y0, left.y0) << where;
      ASSERT_EQ(right.y1, left.y1) << where;
      // The bar (without its left edge, beside the markers), its ticks and the first
      // pixels of their labels, and a few rows above and below for the end labels.
      const int w = left.x1 - left.x0;
      const PixelRect legend{double(left.x0 + 1), double(left.y0 - 6), double(2 * w),
                             double(left.y1 - left.y0 + 12)};
      const invfree::test::ImageDiff d =
          invfree::test::compare_images(crop(image, legend, 0), crop(image, legend, half), 0);
      if (d.differing > 0) ++bars_differ;
    }
    EXPECT_EQ(bars_differ, 0) << what << ": " << bars_differ << " of " << c.frames
                              << " frames scale the two views differently";
  }
}

}  // namespace
