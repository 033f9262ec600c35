#include "app/plot/font.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <utility>

#define STB_TRUETYPE_IMPLEMENTATION
#define STBTT_STATIC
#include <stb/stb_truetype.h>

#include "app/embed_section.h"

// The font file, placed in .rodata by the assembler (INVFREE_CHART_FONT is its absolute
// path, set by app/plot/CMakeLists.txt).
asm(INVFREE_RODATA_OPEN(invfree_chart_font_begin) ".balign 16\n"
    ".globl invfree_chart_font_begin\n"
    "invfree_chart_font_begin:\n"
    ".incbin \"" INVFREE_CHART_FONT "\"\n" INVFREE_RODATA_SIZE(invfree_chart_font_begin)
    ".globl invfree_chart_font_end\n"
    "invfree_chart_font_end:\n"
    ".byte 0\n" INVFREE_RODATA_SIZE(invfree_chart_font_end) INVFREE_RODATA_CLOSE);
extern "C" const unsigned char invfree_chart_font_begin[];
extern "C" const unsigned char invfree_chart_font_end[];

namespace invfree {

namespace {

struct FontState {
  stbtt_fontinfo info{};
  float ascent = 0.0f, descent = 0.0f;  // font units
  std::map<std::pair<char32_t, long>, Glyph> glyphs;
  std::mutex mutex;

  FontState() {
    const int offset = stbtt_GetFontOffsetForIndex(invfree_chart_font_begin, 0);
    if (offset < 0 || !stbtt_InitFont(&info, invfree_chart_font_begin, offset)) {
      std::fprintf(stderr, "invfree: the embedded chart font (%s) is not a TrueType font\n",
                   INVFREE_CHART_FONT);
      std::abort();
    }
    int a = 0, d = 0, gap = 0;
    stbtt_GetFontVMetrics(&info, &a, &d, &gap);
    ascent = static_cast<float>(a);
    descent = static_cast<float>(d);
  }
  float scale(double size_px) const { return static_cast<float>(size_px) / (ascent - descent); }
};

FontState& font() {
  static FontState state;
  return state;
}

}  // namespace

const Glyph& font_glyph(char32_t codepoint, double size_px) {
  FontState& f = font();
  const std::lock_guard lock(f.mutex);
  const auto key = std::make_pair(codepoint, std::lround(size_px * 64.0));
  auto it = f.glyphs.find(key);
  if (it != f.glyphs.end()) return it->second;
  Glyph g;
  const float s = f.scale(size_px);
  int glyph = stbtt_FindGlyphIndex(&f.info, static_cast<int>(codepoint));
  if (glyph == 0 && codepoint != U'?') glyph = stbtt_FindGlyphIndex(&f.info, '?');
  int advance = 0, lsb = 0;
  stbtt_GetGlyphHMetrics(&f.info, glyph, &advance, &lsb);
  g.advance = advance * static_cast<double>(s);
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  stbtt_GetGlyphBitmapBox(&f.info, glyph, s, s, &x0, &y0, &x1, &y1);
  g.width = x1 - x0;
  g.height = y1 - y0;
  g.x_offset = x0;
  g.y_offset = y0;
  if (g.width > 0 && g.height > 0) {
    g.coverage.assign(static_cast<size_t>(g.width) * g.height, 0);
    stbtt_MakeGlyphBitmap(&f.info, g.coverage.data(), g.width, g.height, g.width, s, s, glyph);
  }
  return f.glyphs.emplace(key, std::move(g)).first->second;
}

double font_kerning(char32_t left, char32_t right, double size_px) {
  FontState& f = font();
  return stbtt_GetCodepointKernAdvance(&f.info, static_cast<int>(left), static_cast<int>(right)) *
         static_cast<double>(f.scale(size_px));
}

double font_ascent(double size_px) {
  FontState& f = font();
  return f.ascent * static_cast<double>(f.scale(size_px));
}

}  // namespace invfree
