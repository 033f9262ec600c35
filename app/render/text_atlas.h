// The renderer's text: glyph bitmaps of the DejaVu Sans font embedded in the binary
// (app/plot/font.h, rasterized by stb_truetype) packed into one 8-bit coverage atlas for
// a few pixel sizes, and the layout of a UTF-8 string into glyph quads.
//
// Inputs: the font sizes (font_glyph's size_px) the frame needs. Outputs: the atlas bitmap
// (uploaded to a GL texture by the renderer) and, per string, quads in pixel coordinates
// (x right, y down) with atlas texel coordinates. Glyphs are placed at whole pixels and
// sampled texel for texel, so text is exactly as sharp as stb_truetype made it.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace invfree::render {

std::u32string decode_utf8(std::string_view s);

struct GlyphQuad {
  float x0, y0, x1, y1;  // pixels
  float u0, v0, u1, v1;  // atlas texels
};

class TextAtlas {
 public:
  // Rasterizes the printable ASCII range and the symbols the renderer uses (Greek
  // letters, <=, a middle dot, ...) at each size. Other code points fall back to '?'.
  void build(const std::vector<double>& sizes_px);

  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<std::uint8_t>& pixels() const {
    return pixels_;
  }  // width * height, row 0 first

  // Width in pixels of `utf8` at size index `size` (an index into build's sizes).
  double text_width(std::string_view utf8, int size) const;
  // Ascent of the font at that size (baseline to top of the tallest glyphs).
  double ascent(int size) const;
  // Vertical middle of the glyph's ink relative to the baseline (negative: above it), to
  // centre a symbol on a given y.
  double ink_middle(int size, char32_t c) const;
  // Appends the quads of `utf8` with its baseline starting at (x, baseline).
  void layout(std::string_view utf8, int size, double x, double baseline,
              std::vector<GlyphQuad>* out) const;

 private:
  struct Entry {
    int x = 0, y = 0, w = 0, h = 0;  // in the atlas
    int x_offset = 0, y_offset = 0;  // bitmap top-left relative to the pen on the baseline
    double advance = 0.0;
  };
  const Entry& entry(int size, char32_t c) const;

  std::vector<double> sizes_;
  std::map<std::pair<int, char32_t>, Entry> entries_;
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> pixels_;
};

}  // namespace invfree::render
