#include "app/render/text_atlas.h"

#include <algorithm>
#include <cmath>

#include "app/plot/font.h"

namespace invfree::render {

namespace {

// Symbols beyond ASCII that labels use: mu, lambda, Delta, nu, rho, <=, >=, element-of,
// en dash, middle dot, times, minus, superscripts, arrows, the colour bar's marker.
constexpr char32_t kExtraCodepoints[] = {U'μ', U'λ', U'Δ', U'ν', U'ρ', U'≤', U'≥', U'∈',
                                         U'–', U'·', U'×', U'−', U'²', U'³', U'⁻', U'¹',
                                         U'↑', U'↓', U'°', U'…', U'▶', U'Ψ'};

constexpr int kAtlasWidth = 1024;

}  // namespace

std::u32string decode_utf8(std::string_view s) {
  std::u32string out;
  for (size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    int extra = 0;
    char32_t cp = c;
    if (c >= 0x80) {
      if ((c >> 5) == 0x6)
        extra = 1, cp = c & 0x1F;
      else if ((c >> 4) == 0xE)
        extra = 2, cp = c & 0x0F;
      else if ((c >> 3) == 0x1E)
        extra = 3, cp = c & 0x07;
      else
        extra = -1;
    }
    bool ok = extra >= 0 && i + extra < s.size();
    for (int k = 1; ok && k <= extra; ++k) {
      const auto cc = static_cast<unsigned char>(s[i + k]);
      ok = (cc >> 6) == 0x2;
      cp = (cp << 6) | (cc & 0x3F);
    }
    out.push_back(ok ? cp : U'?');
    i += ok ? extra + 1 : 1;
  }
  return out;
}

void TextAtlas::build(const std::vector<double>& sizes_px) {
  sizes_ = sizes_px;
  entries_.clear();
  std::vector<char32_t> codepoints;
  for (char32_t c = 32; c < 127; ++c) codepoints.push_back(c);
  codepoints.insert(codepoints.end(), std::begin(kExtraCodepoints), std::end(kExtraCodepoints));

  // Shelf packing, one pixel of padding so that no glyph bleeds into its neighbour.
  struct Placed {
    const Glyph* glyph;
    int size;
    char32_t c;
  };
  std::vector<Placed> placed;
  int x = 1, y = 1, shelf = 0;
  for (int s = 0; s < static_cast<int>(sizes_.size()); ++s) {
    for (char32_t c : codepoints) {
      const Glyph& g = font_glyph(c, sizes_[s]);
      if (x + g.width + 1 > kAtlasWidth) {
        x = 1;
        y += shelf + 1;
        shelf = 0;
      }
      Entry e;
      e.x = x;
      e.y = y;
      e.w = g.width;
      e.h = g.height;
      e.x_offset = g.x_offset;
      e.y_offset = g.y_offset;
      e.advance = g.advance;
      entries_[{s, c}] = e;
      placed.push_back({&g, s, c});
      x += g.width + 1;
      shelf = std::max(shelf, g.height);
    }
  }
  width_ = kAtlasWidth;
  height_ = y + shelf + 1;
  pixels_.assign(static_cast<size_t>(width_) * height_, 0);
  for (const Placed& p : placed) {
    const Entry& e = entries_[{p.size, p.c}];
    for (int r = 0; r < e.h; ++r)
      std::copy_n(p.glyph->coverage.data() + static_cast<size_t>(r) * e.w, e.w,
                  pixels_.data() + static_cast<size_t>(e.y + r) * width_ + e.x);
  }
}

const TextAtlas::Entry& TextAtlas::entry(int size, char32_t c) const {
  auto it = entries_.find({size, c});
  if (it == entries_.end()) it = entries_.find({size, U'?'});
  return it->second;
}

double TextAtlas::text_width(std::string_view utf8, int size) const {
  const std::u32string text = decode_utf8(utf8);
  double pen = 0.0;
  for (size_t i = 0; i < text.size(); ++i) {
    if (i > 0) pen += font_kerning(text[i - 1], text[i], sizes_[size]);
    pen += entry(size, text[i]).advance;
  }
  return pen;
}

double TextAtlas::ascent(int size) const {
  return font_ascent(sizes_[size]);
}

double TextAtlas::ink_middle(int size, char32_t c) const {
  const Entry& e = entry(size, c);
  return e.y_offset + 0.5 * e.h;
}

void TextAtlas::layout(std::string_view utf8, int size, double x, double baseline,
                       std::vector<GlyphQuad>* out) const {
  const std::u32string text = decode_utf8(utf8);
  const double base = std::round(baseline);
  double pen = std::round(x);
  for (size_t i = 0; i < text.size(); ++i) {
    if (i > 0) pen += font_kerning(text[i - 1], text[i], sizes_[size]);
    const Entry& e = entry(size, text[i]);
    if (e.w > 0 && e.h > 0) {
      const auto gx = static_cast<float>(std::round(pen) + e.x_offset);
      const auto gy = static_cast<float>(base + e.y_offset);
      out->push_back(
          {gx, gy, gx + e.w, gy + e.h, float(e.x), float(e.y), float(e.x + e.w), float(e.y + e.h)});
    }
    pen += e.advance;
  }
}

}  // namespace invfree::render
