#include "app/live/window_capture.h"

#include <GL/glcorearb.h>

#include <algorithm>

#include "app/live/output_naming.h"

namespace invfree::live {

std::vector<std::uint8_t> read_window_bottom_up(const render::GlApi& gl, int width, int height) {
  std::vector<std::uint8_t> rgba(static_cast<size_t>(width) * height * 4);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  gl.ReadBuffer(GL_BACK);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
  return rgba;
}

Image read_window(const render::GlApi& gl, int width, int height) {
  const std::vector<std::uint8_t> rgba = read_window_bottom_up(gl, width, height);
  Image img;
  img.width = width;
  img.height = height;
  img.rgba.resize(rgba.size());
  const size_t row = static_cast<size_t>(width) * 4;
  for (int y = 0; y < height; ++y)
    std::copy(rgba.begin() + static_cast<long>((height - 1 - y) * row),
              rgba.begin() + static_cast<long>((height - y) * row),
              img.rgba.begin() + static_cast<long>(y * row));
  return img;
}

std::string save_screenshot(const std::string& dir, const Image& image) {
  const std::string path = next_screenshot_path(dir);
  if (const std::string e = write_png(path, image); !e.empty())
    return "invfree: live: screenshot failed: " + e;
  return "screenshot: " + path;
}

}  // namespace invfree::live
