// A drawing surface for charts and contact sheets, backed by Cairo (libcairo2-dev):
// antialiased lines, markers, filled triangles, clipping and text in the DejaVu Sans font
// embedded into invfree (app/plot/font.cpp; FreeType reads it from memory, so charts do
// not depend on the run-time font setup). The same drawing goes to PNG, SVG or PDF.
//
// Coordinates are in points of the drawing (x right, y down; for PNG one point is one
// pixel). Every piece of text drawn is also logged with its box in drawing coordinates
// (texts()), so tests can check what a chart says and that it stays inside the drawing.
// Inputs: drawing calls. Output: finish() returns the encoded file.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/colormap.h"

typedef struct _cairo cairo_t;
typedef struct _cairo_surface cairo_surface_t;

namespace invfree {

enum class ChartFormat { Png, Svg, Pdf };
// "png", "svg" or "pdf" (the --format values); nullopt for anything else.
std::optional<ChartFormat> parse_chart_format(const std::string& name);
const char* chart_extension(ChartFormat format);  // "png", "svg", "pdf"

struct Point2 {
  double x = 0.0, y = 0.0;
};

enum class Align { Left, Center, Right };
enum class MarkerShape { Circle, Square, Diamond, TriangleUp, TriangleDown };

// A piece of text as drawn: its box in drawing coordinates (after any translation).
struct TextItem {
  std::string text;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Text measurement without a drawing (for layouts): width in points at `size` (the font's
// ascent + descent), and words wrapped into lines no wider than `max_width`.
double text_width(const std::string& utf8, double size);
std::vector<std::string> wrap_text(const std::string& utf8, double size, double max_width);

class Canvas {
 public:
  // A white drawing of the given size (at least 1 x 1).
  Canvas(double width, double height, ChartFormat format);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  double width() const { return width_; }
  double height() const { return height_; }

  void fill_rect(double x0, double y0, double x1, double y1, Rgb color, double alpha = 1.0);
  void stroke_rect(double x0, double y0, double x1, double y1, double line_width, Rgb color);
  // Round joins and caps; `dash` > 0 draws dashes of that length.
  void polyline(const std::vector<Point2>& points, double line_width, Rgb color, double alpha = 1.0,
                double dash = 0.0);
  void line(Point2 a, Point2 b, double line_width, Rgb color, double alpha = 1.0) {
    polyline({a, b}, line_width, color, alpha);
  }
  // A filled marker of the given radius with a thin outline.
  void marker(Point2 center, double radius, MarkerShape shape, Rgb fill, Rgb outline);
  void ring(Point2 center, double radius, double line_width, Rgb color);
  // Flat-coloured triangles; neighbours meet without a visible seam.
  void triangles(const std::vector<Point2>& nodes, const std::vector<std::array<int, 3>>& tris,
                 const std::vector<Rgb>& colors);
  // `x, y`: the anchor (horizontally per `align`, vertically the baseline); `vertical`
  // turns the text 90 degrees counter-clockwise (reads bottom to top, `x` its baseline).
  void text(const std::string& utf8, double x, double y, double size, Rgb color,
            Align align = Align::Left, bool vertical = false);

  // Drawing state: push() saves it, pop() restores it (clip and translation included).
  void push();
  void pop();
  void clip(double x0, double y0, double x1, double y1);
  void translate(double dx, double dy);

  const std::vector<TextItem>& texts() const { return texts_; }
  // Finishes the drawing and returns the file's bytes (PNG, SVG or PDF); "" on failure.
  std::string finish();

 private:
  double width_, height_;
  ChartFormat format_;
  std::string vector_bytes_;  // what the SVG / PDF surface wrote
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
  std::vector<TextItem> texts_;
};

// Writes the finished canvas to `path` atomically (app/output_files.h); "" or an error.
std::string write_canvas(const std::string& path, Canvas& canvas);

}  // namespace invfree
