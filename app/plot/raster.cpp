#include "app/plot/raster.h"

#include <algorithm>
#include <cmath>

#include "app/plot/font.h"

namespace invfree {

namespace {

std::uint8_t to_byte(double v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

// A coverage mask over a clipped pixel rectangle of the image: drawing primitives take
// the maximum coverage per pixel, then composite once.
struct Mask {
  int x0 = 0, y0 = 0, w = 0, h = 0;
  std::vector<float> cov;
  Mask(const Image& img, double fx0, double fy0, double fx1, double fy1) {
    x0 = std::max(0, static_cast<int>(std::floor(fx0)));
    y0 = std::max(0, static_cast<int>(std::floor(fy0)));
    const int x1 = std::min(img.width, static_cast<int>(std::ceil(fx1)) + 1);
    const int y1 = std::min(img.height, static_cast<int>(std::ceil(fy1)) + 1);
    w = std::max(0, x1 - x0);
    h = std::max(0, y1 - y0);
    cov.assign(static_cast<size_t>(w) * h, 0.0f);
  }
  float& at(int x, int y) { return cov[static_cast<size_t>(y - y0) * w + (x - x0)]; }
  void composite(Image& img, Rgb color, double alpha) const {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float c = cov[static_cast<size_t>(y) * w + x];
        if (c > 0.0f) blend_pixel(img, x0 + x, y0 + y, color, c * alpha);
      }
  }
};

double segment_distance(Point2 p, Point2 a, Point2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

// Signed distance (negative inside) to a convex polygon given counter-clockwise or
// clockwise: the largest signed distance to its edge lines (exact except near corners).
double convex_distance(Point2 p, const std::vector<Point2>& poly) {
  double area2 = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Point2 a = poly[i], b = poly[(i + 1) % poly.size()];
    area2 += a.x * b.y - b.x * a.y;
  }
  const double orient = area2 >= 0.0 ? 1.0 : -1.0;
  double d = -1e300;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Point2 a = poly[i], b = poly[(i + 1) % poly.size()];
    const double ex = b.x - a.x, ey = b.y - a.y;
    const double len = std::hypot(ex, ey);
    if (len == 0.0) continue;
    // Outward normal of a counter-clockwise (in y-up terms) edge.
    const double nx = orient * ey / len, ny = -orient * ex / len;
    d = std::max(d, (p.x - a.x) * nx + (p.y - a.y) * ny);
  }
  return d;
}

std::vector<Point2> marker_polygon(Point2 c, double r, MarkerShape shape) {
  switch (shape) {
    case MarkerShape::Square: {
      const double s = r * 0.85;
      return {{c.x - s, c.y - s}, {c.x + s, c.y - s}, {c.x + s, c.y + s}, {c.x - s, c.y + s}};
    }
    case MarkerShape::Diamond: {
      const double s = r * 1.15;
      return {{c.x, c.y - s}, {c.x + s, c.y}, {c.x, c.y + s}, {c.x - s, c.y}};
    }
    case MarkerShape::TriangleUp:
    case MarkerShape::TriangleDown: {
      const double s = r * 1.25, sign = shape == MarkerShape::TriangleUp ? 1.0 : -1.0;
      return {{c.x, c.y - sign * s},
              {c.x + s * 0.866, c.y + sign * s * 0.5},
              {c.x - s * 0.866, c.y + sign * s * 0.5}};
    }
    case MarkerShape::Circle:
      break;
  }
  return {};
}

std::u32string decode_utf8(const std::string& s) {
  std::u32string out;
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    int n = 0;
    char32_t cp = c;
    if (c >= 0x80) {
      if ((c >> 5) == 6) {
        n = 1, cp = c & 0x1F;
      } else if ((c >> 4) == 14) {
        n = 2, cp = c & 0x0F;
      } else if ((c >> 3) == 30) {
        n = 3, cp = c & 0x07;
      } else {
        out.push_back(U'?');
        ++i;
        continue;
      }
    }
    bool ok = i + n < s.size();
    for (int k = 1; ok && k <= n; ++k) {
      const unsigned char cc = static_cast<unsigned char>(s[i + k]);
      ok = (cc >> 6) == 2;
      cp = (cp << 6) | (cc & 0x3F);
    }
    out.push_back(ok ? cp : U'?');
    i += ok ? n + 1 : 1;
  }
  return out;
}

// Text rendered into a coverage mask; (origin_x, baseline) is the pen start inside it.
struct TextMask {
  int w = 0, h = 0, baseline = 0;
  double advance = 0.0;
  std::vector<float> cov;
};

TextMask render_text_mask(const std::string& utf8, double size_px) {
  const std::u32string text = decode_utf8(utf8);
  TextMask m;
  // First pass: extent.
  double pen = 0.0;
  int top = 0, bottom = 0, right = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    if (i > 0) pen += font_kerning(text[i - 1], text[i], size_px);
    const Glyph& g = font_glyph(text[i], size_px);
    top = std::min(top, g.y_offset);
    bottom = std::max(bottom, g.y_offset + g.height);
    right = std::max(right, static_cast<int>(std::lround(pen)) + g.x_offset + g.width);
    pen += g.advance;
  }
  m.advance = pen;
  m.baseline = -top;
  m.w = std::max(right, static_cast<int>(std::ceil(pen))) + 1;
  m.h = bottom - top;
  if (m.w <= 0 || m.h <= 0) return m;
  m.cov.assign(static_cast<size_t>(m.w) * m.h, 0.0f);
  pen = 0.0;
  for (size_t i = 0; i < text.size(); ++i) {
    if (i > 0) pen += font_kerning(text[i - 1], text[i], size_px);
    const Glyph& g = font_glyph(text[i], size_px);
    const int gx = static_cast<int>(std::lround(pen)) + g.x_offset;
    const int gy = m.baseline + g.y_offset;
    for (int y = 0; y < g.height; ++y)
      for (int x = 0; x < g.width; ++x) {
        const int px = gx + x, py = gy + y;
        if (px < 0 || py < 0 || px >= m.w || py >= m.h) continue;
        float& c = m.cov[static_cast<size_t>(py) * m.w + px];
        c = std::min(1.0f, c + g.coverage[static_cast<size_t>(y) * g.width + x] / 255.0f);
      }
    pen += g.advance;
  }
  return m;
}

}  // namespace

Image make_image(int width, int height, Rgb background) {
  Image img;
  img.width = std::max(0, width);
  img.height = std::max(0, height);
  img.rgba.resize(static_cast<size_t>(img.width) * img.height * 4);
  const std::uint8_t r = to_byte(background.r), g = to_byte(background.g),
                     b = to_byte(background.b);
  for (size_t i = 0; i < img.rgba.size(); i += 4) {
    img.rgba[i] = r;
    img.rgba[i + 1] = g;
    img.rgba[i + 2] = b;
    img.rgba[i + 3] = 255;
  }
  return img;
}

std::array<int, 3> pixel_rgb(const Image& image, int x, int y) {
  const size_t i = (static_cast<size_t>(y) * image.width + x) * 4;
  return {image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]};
}

void blend_pixel(Image& image, int x, int y, Rgb color, double alpha) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  alpha = std::clamp(alpha, 0.0, 1.0);
  if (alpha <= 0.0) return;
  std::uint8_t* p = &image.rgba[(static_cast<size_t>(y) * image.width + x) * 4];
  const double src[3] = {color.r, color.g, color.b};
  for (int k = 0; k < 3; ++k) {
    const double dst = p[k] / 255.0;
    p[k] = to_byte(dst + (src[k] - dst) * alpha);
  }
  p[3] = 255;
}

void fill_rect(Image& image, double x0, double y0, double x1, double y1, Rgb color, double alpha) {
  if (!(x1 > x0 && y1 > y0)) return;
  const int ix0 = std::max(0, static_cast<int>(std::floor(x0)));
  const int iy0 = std::max(0, static_cast<int>(std::floor(y0)));
  const int ix1 = std::min(image.width, static_cast<int>(std::ceil(x1)));
  const int iy1 = std::min(image.height, static_cast<int>(std::ceil(y1)));
  for (int y = iy0; y < iy1; ++y) {
    const double cy = std::min<double>(y + 1, y1) - std::max<double>(y, y0);
    for (int x = ix0; x < ix1; ++x) {
      const double cx = std::min<double>(x + 1, x1) - std::max<double>(x, x0);
      blend_pixel(image, x, y, color, alpha * cx * cy);
    }
  }
}

void stroke_rect(Image& image, double x0, double y0, double x1, double y1, double width,
                 Rgb color) {
  const double w = width / 2.0;
  fill_rect(image, x0 - w, y0 - w, x1 + w, y0 + w, color);
  fill_rect(image, x0 - w, y1 - w, x1 + w, y1 + w, color);
  fill_rect(image, x0 - w, y0 + w, x0 + w, y1 - w, color);
  fill_rect(image, x1 - w, y0 + w, x1 + w, y1 - w, color);
}

void draw_polyline(Image& image, const std::vector<Point2>& points, double width, Rgb color,
                   double alpha) {
  if (points.empty() || !(width > 0.0)) return;
  // Lines thinner than a pixel are drawn one pixel wide and correspondingly fainter.
  const double half = std::max(width, 1.0) / 2.0;
  const double faint = std::min(width, 1.0);
  double bx0 = 1e300, by0 = 1e300, bx1 = -1e300, by1 = -1e300;
  for (const Point2& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
    bx0 = std::min(bx0, p.x);
    by0 = std::min(by0, p.y);
    bx1 = std::max(bx1, p.x);
    by1 = std::max(by1, p.y);
  }
  Mask mask(image, bx0 - half - 1.0, by0 - half - 1.0, bx1 + half + 1.0, by1 + half + 1.0);
  if (mask.w == 0 || mask.h == 0) return;
  const size_t segments = points.size() == 1 ? 1 : points.size() - 1;
  for (size_t s = 0; s < segments; ++s) {
    const Point2 a = points[s], b = points[std::min(s + 1, points.size() - 1)];
    const int x0 = std::max(mask.x0, static_cast<int>(std::floor(std::min(a.x, b.x) - half - 1.0)));
    const int x1 = std::min(mask.x0 + mask.w - 1,
                            static_cast<int>(std::ceil(std::max(a.x, b.x) + half + 1.0)));
    const int y0 = std::max(mask.y0, static_cast<int>(std::floor(std::min(a.y, b.y) - half - 1.0)));
    const int y1 = std::min(mask.y0 + mask.h - 1,
                            static_cast<int>(std::ceil(std::max(a.y, b.y) + half + 1.0)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double d = segment_distance({x + 0.5, y + 0.5}, a, b);
        const float c = static_cast<float>(std::clamp(half + 0.5 - d, 0.0, 1.0) * faint);
        float& m = mask.at(x, y);
        m = std::max(m, c);
      }
  }
  mask.composite(image, color, alpha);
}

void draw_marker(Image& image, Point2 c, double r, MarkerShape shape, Rgb fill, Rgb outline) {
  if (!std::isfinite(c.x) || !std::isfinite(c.y) || !(r > 0.0)) return;
  const double reach = r * 1.3 + 2.0;
  Mask inside(image, c.x - reach, c.y - reach, c.x + reach, c.y + reach);
  Mask edge(image, c.x - reach, c.y - reach, c.x + reach, c.y + reach);
  const std::vector<Point2> poly = marker_polygon(c, r, shape);
  const double outline_half = 0.6;
  for (int y = inside.y0; y < inside.y0 + inside.h; ++y)
    for (int x = inside.x0; x < inside.x0 + inside.w; ++x) {
      const Point2 p{x + 0.5, y + 0.5};
      const double sd = shape == MarkerShape::Circle ? std::hypot(p.x - c.x, p.y - c.y) - r
                                                     : convex_distance(p, poly);
      inside.at(x, y) = static_cast<float>(std::clamp(0.5 - sd, 0.0, 1.0));
      edge.at(x, y) = static_cast<float>(std::clamp(outline_half + 0.5 - std::abs(sd), 0.0, 1.0));
    }
  inside.composite(image, fill, 1.0);
  edge.composite(image, outline, 1.0);
}

void draw_ring(Image& image, Point2 c, double r, double width, Rgb color) {
  if (!std::isfinite(c.x) || !std::isfinite(c.y) || !(r > 0.0)) return;
  const double reach = r + width + 2.0;
  Mask ring(image, c.x - reach, c.y - reach, c.x + reach, c.y + reach);
  for (int y = ring.y0; y < ring.y0 + ring.h; ++y)
    for (int x = ring.x0; x < ring.x0 + ring.w; ++x) {
      const double d = std::abs(std::hypot(x + 0.5 - c.x, y + 0.5 - c.y) - r);
      ring.at(x, y) = static_cast<float>(std::clamp(width / 2.0 + 0.5 - d, 0.0, 1.0));
    }
  ring.composite(image, color, 1.0);
}

void fill_mesh(Image& image, const std::vector<Point2>& nodes,
               const std::vector<std::array<int, 3>>& triangles, const std::vector<Rgb>& colors) {
  constexpr int S = 4;  // subsamples per pixel side
  double bx0 = 1e300, by0 = 1e300, bx1 = -1e300, by1 = -1e300;
  for (const auto& t : triangles)
    for (int k : t) {
      const Point2 p = nodes[k];
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      bx0 = std::min(bx0, p.x);
      by0 = std::min(by0, p.y);
      bx1 = std::max(bx1, p.x);
      by1 = std::max(by1, p.y);
    }
  if (!(bx1 >= bx0)) return;
  Mask box(image, bx0, by0, bx1, by1);
  if (box.w == 0 || box.h == 0) return;
  const int sw = box.w * S, sh = box.h * S;
  std::vector<int> owner(static_cast<size_t>(sw) * sh, -1);
  for (size_t t = 0; t < triangles.size(); ++t) {
    Point2 p[3];
    bool finite = true;
    for (int k = 0; k < 3; ++k) {
      p[k] = nodes[triangles[t][k]];
      finite = finite && std::isfinite(p[k].x) && std::isfinite(p[k].y);
    }
    if (!finite) continue;
    // Subsample (i, j) sits at image position box.x0 + (i + 0.5) / S.
    auto to_sub = [&](double v, int origin) { return (v - origin) * S - 0.5; };
    const double xs[3] = {to_sub(p[0].x, box.x0), to_sub(p[1].x, box.x0), to_sub(p[2].x, box.x0)};
    const double ys[3] = {to_sub(p[0].y, box.y0), to_sub(p[1].y, box.y0), to_sub(p[2].y, box.y0)};
    const int i0 = std::max(0, static_cast<int>(std::ceil(std::min({xs[0], xs[1], xs[2]}))));
    const int i1 = std::min(sw - 1, static_cast<int>(std::floor(std::max({xs[0], xs[1], xs[2]}))));
    const int j0 = std::max(0, static_cast<int>(std::ceil(std::min({ys[0], ys[1], ys[2]}))));
    const int j1 = std::min(sh - 1, static_cast<int>(std::floor(std::max({ys[0], ys[1], ys[2]}))));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        double e[3];
        for (int k = 0; k < 3; ++k) {
          const int l = (k + 1) % 3;
          e[k] = (xs[l] - xs[k]) * (j - ys[k]) - (ys[l] - ys[k]) * (i - xs[k]);
        }
        const bool in =
            (e[0] >= 0 && e[1] >= 0 && e[2] >= 0) || (e[0] <= 0 && e[1] <= 0 && e[2] <= 0);
        if (in) owner[static_cast<size_t>(j) * sw + i] = static_cast<int>(t);
      }
  }
  for (int y = 0; y < box.h; ++y)
    for (int x = 0; x < box.w; ++x) {
      double r = 0, g = 0, b = 0;
      int n = 0;
      for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
          const int o = owner[static_cast<size_t>(y * S + j) * sw + (x * S + i)];
          if (o < 0) continue;
          r += colors[o].r;
          g += colors[o].g;
          b += colors[o].b;
          ++n;
        }
      if (n == 0) continue;
      const Rgb avg{static_cast<float>(r / n), static_cast<float>(g / n),
                    static_cast<float>(b / n)};
      blend_pixel(image, box.x0 + x, box.y0 + y, avg, static_cast<double>(n) / (S * S));
    }
}

double text_width(const std::string& utf8, double size_px) {
  const std::u32string text = decode_utf8(utf8);
  double pen = 0.0;
  for (size_t i = 0; i < text.size(); ++i) {
    if (i > 0) pen += font_kerning(text[i - 1], text[i], size_px);
    pen += font_glyph(text[i], size_px).advance;
  }
  return pen;
}

void draw_text(Image& image, const std::string& utf8, double x, double y, double size_px, Rgb color,
               Align align) {
  const TextMask m = render_text_mask(utf8, size_px);
  const double shift = align == Align::Left     ? 0.0
                       : align == Align::Center ? m.advance / 2.0
                                                : m.advance;
  const int ox = static_cast<int>(std::lround(x - shift));
  const int oy = static_cast<int>(std::lround(y)) - m.baseline;
  for (int j = 0; j < m.h; ++j)
    for (int i = 0; i < m.w; ++i) {
      const float c = m.cov[static_cast<size_t>(j) * m.w + i];
      if (c > 0.0f) blend_pixel(image, ox + i, oy + j, color, c);
    }
}

void draw_text_vertical(Image& image, const std::string& utf8, double x, double y, double size_px,
                        Rgb color) {
  const TextMask m = render_text_mask(utf8, size_px);
  // Rotating counter-clockwise: mask column i goes to image row (oy - i), mask row j to
  // image column (ox + j); the baseline row lands on column x.
  const int ox = static_cast<int>(std::lround(x)) - m.baseline;
  const int oy = static_cast<int>(std::lround(y + m.advance / 2.0));
  for (int j = 0; j < m.h; ++j)
    for (int i = 0; i < m.w; ++i) {
      const float c = m.cov[static_cast<size_t>(j) * m.w + i];
      if (c > 0.0f) blend_pixel(image, ox + j, oy - i, color, c);
    }
}

std::vector<std::string> wrap_text(const std::string& utf8, double size_px, double max_width) {
  std::vector<std::string> lines;
  std::string line, word;
  auto flush_word = [&] {
    if (word.empty()) return;
    const std::string candidate = line.empty() ? word : line + " " + word;
    if (!line.empty() && text_width(candidate, size_px) > max_width) {
      lines.push_back(line);
      line = word;
    } else {
      line = candidate;
    }
    word.clear();
  };
  for (char ch : utf8) {
    if (ch == ' ') {
      flush_word();
    } else if (ch == '\n') {
      flush_word();
      lines.push_back(line);
      line.clear();
    } else {
      word.push_back(ch);
    }
  }
  flush_word();
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

void blit(Image& dst, const Image& src, int x, int y) {
  for (int j = 0; j < src.height; ++j) {
    const int dy = y + j;
    if (dy < 0 || dy >= dst.height) continue;
    for (int i = 0; i < src.width; ++i) {
      const int dx = x + i;
      if (dx < 0 || dx >= dst.width) continue;
      const size_t s = (static_cast<size_t>(j) * src.width + i) * 4;
      const size_t d = (static_cast<size_t>(dy) * dst.width + dx) * 4;
      for (int k = 0; k < 4; ++k) dst.rgba[d + k] = src.rgba[s + k];
    }
  }
}

}  // namespace invfree
