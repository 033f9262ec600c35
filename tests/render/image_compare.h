// Screenshot comparison for the golden tests. The rule: two images match when
// at most 0.1% of their pixels differ by more than 5/255 in any channel. On a mismatch
// (or a missing golden) the caller gets the counts and the paths of the actual, expected
// and amplified-difference images written for a person to look at.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace invfree::test {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // top row first
};

// RGBA8 bottom row first (Renderer::read_pixels) -> RGB top row first.
RgbImage from_gl_pixels(const std::vector<std::uint8_t>& rgba_bottom_up, int width, int height);
// Loads a PNG as RGB; false when missing or unreadable.
bool load_png(const std::string& path, RgbImage* image);
std::string save_png(const std::string& path, const RgbImage& image);  // "" or an error

struct ImageDiff {
  bool same_size = false;
  long pixels = 0;     // pixels compared
  long differing = 0;  // pixels differing by more than the threshold in some channel
  int max_channel_diff = 0;
  bool matches(double max_fraction = 0.001) const {
    return same_size && differing <= static_cast<long>(max_fraction * pixels);
  }
};

ImageDiff compare_images(const RgbImage& actual, const RgbImage& expected, int threshold = 5);
// The expected image faded to a light grey, darkened by 16x the per-pixel difference
// (so differences under the threshold show), and pixels over the threshold in magenta.
RgbImage difference_image(const RgbImage& actual, const RgbImage& expected, int threshold = 5);

// Compares `actual` with golden `golden_dir/name.png`. With the environment variable
// INVFREE_UPDATE_GOLDENS=1 it writes the golden instead. Returns "" when it matches (or
// was written); otherwise a message with the counts, the paths of
// `failure_dir/name_{actual,expected,diff}.png`, and for a missing golden how to make it.
std::string check_golden(const RgbImage& actual, const std::string& name,
                         const std::string& golden_dir, const std::string& failure_dir);

}  // namespace invfree::test
