// A plain RGBA8 picture (live-mode screenshots, rendered frames) and its PNG writer
// (stb_image_write, app/plot/png.cpp). Charts are drawn with Cairo instead (canvas.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace invfree {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes, row-major, top row first
};

// Writes `image` as a PNG, atomically (app/output_files.h). Returns "" or a one-line error.
std::string write_png(const std::string& path, const Image& image);

}  // namespace invfree
