// The CPU rasterizer under app/plot: antialiased drawing into an Image (RGBA8, see
// chart.h) in pixel coordinates (x right, y down; pixel (i, j) covers [i, i+1) x [j, j+1)).
// Everything is composited "over" with a coverage alpha, so drawing is order dependent
// and never reads outside the image. Text uses the DejaVu Sans font embedded at build
// time (font.h). Used by the charts and by the stability contact sheet.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "app/plot/chart.h"

namespace invfree {

struct Point2 {
  double x = 0.0, y = 0.0;
};

Image make_image(int width, int height, Rgb background);
// Colour of pixel (x, y) as 0..255 RGB (for tests and for blits).
std::array<int, 3> pixel_rgb(const Image& image, int x, int y);

// Composites `color` over pixel (x, y) with opacity `alpha` in [0, 1]; outside: ignored.
void blend_pixel(Image& image, int x, int y, Rgb color, double alpha);
// Axis-aligned rectangle [x0, x1) x [y0, y1) with antialiased (fractional) edges.
void fill_rect(Image& image, double x0, double y0, double x1, double y1, Rgb color,
               double alpha = 1.0);
void stroke_rect(Image& image, double x0, double y0, double x1, double y1, double width, Rgb color);

// A polyline of the given width with round joins and caps; each pixel is covered once,
// so overlapping segments of one polyline do not darken.
void draw_polyline(Image& image, const std::vector<Point2>& points, double width, Rgb color,
                   double alpha = 1.0);
inline void draw_line(Image& image, Point2 a, Point2 b, double width, Rgb color,
                      double alpha = 1.0) {
  draw_polyline(image, {a, b}, width, color, alpha);
}

enum class MarkerShape { Circle, Square, Diamond, TriangleUp, TriangleDown };
// A filled marker of the given radius (half its size) with a thin outline.
void draw_marker(Image& image, Point2 center, double radius, MarkerShape shape, Rgb fill,
                 Rgb outline);
// A ring (unfilled circle): used to highlight points.
void draw_ring(Image& image, Point2 center, double radius, double width, Rgb color);

// A triangle mesh with one flat colour per triangle, antialiased on the outline but without
// seams between neighbours (4x4 supersampling of the whole mesh, then one composite).
void fill_mesh(Image& image, const std::vector<Point2>& nodes,
               const std::vector<std::array<int, 3>>& triangles, const std::vector<Rgb>& colors);

// Text. `x, y` is the anchor: horizontally per `align`, vertically the baseline.
enum class Align { Left, Center, Right };
double text_width(const std::string& utf8, double size_px);
void draw_text(Image& image, const std::string& utf8, double x, double y, double size_px, Rgb color,
               Align align = Align::Left);
// Text rotated 90 degrees counter-clockwise (reads bottom to top), centred on (x, y)
// along its length; `x` is its baseline.
void draw_text_vertical(Image& image, const std::string& utf8, double x, double y, double size_px,
                        Rgb color);
// Splits text into lines no wider than `max_width` pixels (at word boundaries).
std::vector<std::string> wrap_text(const std::string& utf8, double size_px, double max_width);

// Copies `src` into `dst` with its top-left corner at (x, y), clipped.
void blit(Image& dst, const Image& src, int x, int y);

}  // namespace invfree
