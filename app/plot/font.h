// The chart font: DejaVu Sans (fonts-dejavu-core), embedded into the binary at build time
// (app/plot/CMakeLists.txt fails the configure step with a clear message when the file is
// missing), so charts never depend on the run-time font setup. Glyph bitmaps are
// rasterized by stb_truetype and cached per (code point, pixel size).
#pragma once

#include <cstdint>
#include <vector>

namespace invfree {

struct Glyph {
  int width = 0, height = 0;           // coverage bitmap size
  int x_offset = 0, y_offset = 0;      // bitmap top-left relative to the pen on the baseline
  double advance = 0.0;                // pen advance in pixels
  std::vector<std::uint8_t> coverage;  // width * height, 0..255
};

// The glyph of `codepoint` at `size_px` (the font's ascent - descent in pixels).
const Glyph& font_glyph(char32_t codepoint, double size_px);
// Kerning adjustment in pixels between two code points.
double font_kerning(char32_t left, char32_t right, double size_px);
// Ascent (positive, above the baseline) in pixels.
double font_ascent(double size_px);

}  // namespace invfree
