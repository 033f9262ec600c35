// The window as shown (the picture with the panel over it), read back from its back buffer
// before the swap: for the recording, a test's capture and screenshots. The window is
// opaque, so alpha is 255 whatever GL left there.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/plot/image.h"
#include "app/render/gl_api.h"

namespace invfree::live {

// RGBA8, bottom row first (GL's order, which the PNG-sequence writer takes).
std::vector<std::uint8_t> read_window_bottom_up(const render::GlApi& gl, int width, int height);
// Top row first.
Image read_window(const render::GlApi& gl, int width, int height);

// Writes `image` as the next DIR/invfree_NNNN.png (output_naming.h). Returns the line that
// tells the user where, or why it failed.
std::string save_screenshot(const std::string& dir, const Image& image);

}  // namespace invfree::live
