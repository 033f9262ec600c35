#include "tests/render/image_compare.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

#include "app/render/frame_writer.h"

namespace invfree::test {

RgbImage from_gl_pixels(const std::vector<std::uint8_t>& rgba, int width, int height) {
  RgbImage img{width, height, std::vector<std::uint8_t>(static_cast<size_t>(width) * height * 3)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        img.rgb[(static_cast<size_t>(y) * width + x) * 3 + c] =
            rgba[(static_cast<size_t>(height - 1 - y) * width + x) * 4 + c];
  return img;
}

bool load_png(const std::string& path, RgbImage* image) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
  if (data == nullptr) return false;
  image->width = w;
  image->height = h;
  image->rgb.assign(data, data + static_cast<size_t>(w) * h * 3);
  stbi_image_free(data);
  return true;
}

std::string save_png(const std::string& path, const RgbImage& image) {
  // The frame writer's encoder takes GL order (RGBA, bottom row first).
  std::vector<std::uint8_t> rgba(static_cast<size_t>(image.width) * image.height * 4, 255);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        rgba[(static_cast<size_t>(image.height - 1 - y) * image.width + x) * 4 + c] =
            image.rgb[(static_cast<size_t>(y) * image.width + x) * 3 + c];
  // Level 9: goldens are committed, so smaller is worth the time.
  return render::write_png_file(path, rgba.data(), image.width, image.height, 9);
}

ImageDiff compare_images(const RgbImage& a, const RgbImage& e, int threshold) {
  ImageDiff d;
  d.same_size = a.width == e.width && a.height == e.height && a.rgb.size() == e.rgb.size();
  if (!d.same_size) return d;
  d.pixels = static_cast<long>(a.width) * a.height;
  for (long p = 0; p < d.pixels; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(int(a.rgb[3 * p + c]) - int(e.rgb[3 * p + c])));
    d.max_channel_diff = std::max(d.max_channel_diff, worst);
    if (worst > threshold) ++d.differing;
  }
  return d;
}

RgbImage difference_image(const RgbImage& a, const RgbImage& e, int threshold) {
  RgbImage d{e.width, e.height, std::vector<std::uint8_t>(e.rgb.size())};
  for (size_t p = 0; p + 2 < e.rgb.size() && p + 2 < a.rgb.size(); p += 3) {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(int(a.rgb[p + c]) - int(e.rgb[p + c])));
    const int grey = (e.rgb[p] + e.rgb[p + 1] + e.rgb[p + 2]) / 3;
    const int faint = 200 + grey / 5;  // the picture, faded, for orientation
    const int amp = std::min(255, worst * 16);
    if (worst > threshold) {
      d.rgb[p] = 255, d.rgb[p + 1] = 0, d.rgb[p + 2] = 255;  // over the threshold: magenta
    } else {
      const auto v = static_cast<std::uint8_t>(std::max(0, faint - amp));
      d.rgb[p] = d.rgb[p + 1] = d.rgb[p + 2] = v;
    }
  }
  return d;
}

std::string check_golden(const RgbImage& actual, const std::string& name,
                         const std::string& golden_dir, const std::string& failure_dir) {
  const std::string golden = golden_dir + "/" + name + ".png";
  const char* update = std::getenv("INVFREE_UPDATE_GOLDENS");
  if (update != nullptr && std::string(update) == "1") {
    if (auto e = save_png(golden, actual); !e.empty()) return "cannot write golden: " + e;
    return "";
  }
  std::filesystem::create_directories(failure_dir);
  const std::string actual_path = failure_dir + "/" + name + "_actual.png";
  RgbImage expected;
  if (!load_png(golden, &expected)) {
    save_png(actual_path, actual);
    return "golden " + golden + " is missing (or unreadable); the actual frame is in " +
           actual_path +
           ". Look at it; if it is right, make the goldens with tests/render/regenerate_goldens.sh";
  }
  const ImageDiff d = compare_images(actual, expected);
  if (d.matches()) return "";
  const std::string expected_path = failure_dir + "/" + name + "_expected.png";
  const std::string diff_path = failure_dir + "/" + name + "_diff.png";
  save_png(actual_path, actual);
  save_png(expected_path, expected);
  if (!d.same_size)
    return name + ": size " + std::to_string(actual.width) + "x" + std::to_string(actual.height) +
           " differs from the golden's " + std::to_string(expected.width) + "x" +
           std::to_string(expected.height) + "; actual: " + actual_path +
           ", expected: " + expected_path;
  save_png(diff_path, difference_image(actual, expected));
  return name + ": " + std::to_string(d.differing) + " of " + std::to_string(d.pixels) +
         " pixels differ by more than 5/255 (allowed: " +
         std::to_string(static_cast<long>(0.001 * d.pixels)) + ", largest channel difference " +
         std::to_string(d.max_channel_diff) + "/255); actual: " + actual_path +
         ", expected: " + expected_path + ", amplified difference: " + diff_path +
         ". If the change is intended, regenerate with tests/render/regenerate_goldens.sh";
}

}  // namespace invfree::test
