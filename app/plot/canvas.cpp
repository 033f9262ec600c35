#include "app/plot/canvas.h"

#include <cairo-ft.h>
#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "app/output_files.h"

// The DejaVu Sans file embedded by app/plot/font.cpp.
extern "C" const unsigned char invfree_chart_font_begin[];
extern "C" const unsigned char invfree_chart_font_end[];

namespace invfree {

namespace {

// The embedded font as a Cairo font face, and the ratio of its ascent + descent to its
// em size (text sizes here are ascent + descent, as in app/plot/font.h). Lives as long as
// the process.
struct ChartFont {
  cairo_font_face_t* face = nullptr;
  double extent_per_em = 1.0;

  ChartFont() {
    FT_Library library = nullptr;
    FT_Face ft_face = nullptr;
    if (FT_Init_FreeType(&library) != 0 ||
        FT_New_Memory_Face(library, invfree_chart_font_begin,
                           static_cast<FT_Long>(invfree_chart_font_end - invfree_chart_font_begin),
                           0, &ft_face) != 0) {
      std::fprintf(stderr, "invfree: the embedded chart font cannot be read by FreeType\n");
      std::abort();
    }
    extent_per_em = double(ft_face->ascender - ft_face->descender) / ft_face->units_per_EM;
    face = cairo_ft_font_face_create_for_ft_face(ft_face, 0);
  }
};

const ChartFont& chart_font() {
  static const ChartFont font;
  return font;
}

// Unhinted outlines and metrics: the same layout at every size and in every format.
void use_chart_font(cairo_t* cr, double size) {
  const ChartFont& font = chart_font();
  cairo_set_font_face(cr, font.face);
  cairo_set_font_size(cr, size / font.extent_per_em);
  cairo_font_options_t* options = cairo_font_options_create();
  cairo_font_options_set_hint_style(options, CAIRO_HINT_STYLE_NONE);
  cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
  cairo_set_font_options(cr, options);
  cairo_font_options_destroy(options);
}

// A 1 x 1 context for measuring text outside any drawing.
cairo_t* measuring_context() {
  thread_local struct Scratch {
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1);
    cairo_t* cr = cairo_create(surface);
    ~Scratch() {
      cairo_destroy(cr);
      cairo_surface_destroy(surface);
    }
  } scratch;
  return scratch.cr;
}

double measured_width(cairo_t* cr, const std::string& utf8, double size) {
  use_chart_font(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, utf8.c_str(), &e);
  return e.x_advance;
}

cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void set_color(cairo_t* cr, Rgb c, double alpha = 1.0) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha);
}

}  // namespace

std::optional<ChartFormat> parse_chart_format(const std::string& name) {
  if (name == "png") return ChartFormat::Png;
  if (name == "svg") return ChartFormat::Svg;
  if (name == "pdf") return ChartFormat::Pdf;
  return std::nullopt;
}

const char* chart_extension(ChartFormat format) {
  switch (format) {
    case ChartFormat::Svg:
      return "svg";
    case ChartFormat::Pdf:
      return "pdf";
    case ChartFormat::Png:
      break;
  }
  return "png";
}

double text_width(const std::string& utf8, double size) {
  return measured_width(measuring_context(), utf8, size);
}

std::vector<std::string> wrap_text(const std::string& utf8, double size, double max_width) {
  std::vector<std::string> lines;
  std::string line, word;
  auto flush_word = [&] {
    if (word.empty()) return;
    const std::string candidate = line.empty() ? word : line + " " + word;
    if (!line.empty() && text_width(candidate, size) > max_width) {
      lines.push_back(line);
      line = word;
    } else {
      line = candidate;
    }
    word.clear();
  };
  for (char c : utf8) {
    if (c == ' ' || c == '\n') {
      flush_word();
      if (c == '\n') {
        lines.push_back(line);
        line.clear();
      }
    } else {
      word += c;
    }
  }
  flush_word();
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

Canvas::Canvas(double width, double height, ChartFormat format)
    : width_(std::max(1.0, std::ceil(width))),
      height_(std::max(1.0, std::ceil(height))),
      format_(format) {
  switch (format) {
    case ChartFormat::Png:
      surface_ = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, static_cast<int>(width_),
                                            static_cast<int>(height_));
      break;
    case ChartFormat::Svg:
      surface_ = cairo_svg_surface_create_for_stream(append_bytes, &vector_bytes_, width_, height_);
      break;
    case ChartFormat::Pdf:
      surface_ = cairo_pdf_surface_create_for_stream(append_bytes, &vector_bytes_, width_, height_);
      break;
  }
  cr_ = cairo_create(surface_);
  cairo_set_source_rgb(cr_, 1.0, 1.0, 1.0);
  cairo_paint(cr_);
  cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
}

Canvas::~Canvas() {
  cairo_destroy(cr_);
  cairo_surface_destroy(surface_);
}

void Canvas::fill_rect(double x0, double y0, double x1, double y1, Rgb color, double alpha) {
  cairo_rectangle(cr_, x0, y0, x1 - x0, y1 - y0);
  set_color(cr_, color, alpha);
  cairo_fill(cr_);
}

void Canvas::stroke_rect(double x0, double y0, double x1, double y1, double line_width, Rgb color) {
  cairo_rectangle(cr_, x0, y0, x1 - x0, y1 - y0);
  set_color(cr_, color);
  cairo_set_line_width(cr_, line_width);
  cairo_stroke(cr_);
}

void Canvas::polyline(const std::vector<Point2>& points, double line_width, Rgb color, double alpha,
                      double dash) {
  if (points.size() < 2) return;
  cairo_move_to(cr_, points[0].x, points[0].y);
  for (size_t i = 1; i < points.size(); ++i) cairo_line_to(cr_, points[i].x, points[i].y);
  set_color(cr_, color, alpha);
  cairo_set_line_width(cr_, line_width);
  const double dashes[] = {dash, dash * 0.6};
  cairo_set_dash(cr_, dashes, dash > 0.0 ? 2 : 0, 0.0);
  cairo_stroke(cr_);
  cairo_set_dash(cr_, nullptr, 0, 0.0);
}

void Canvas::marker(Point2 c, double r, MarkerShape shape, Rgb fill, Rgb outline) {
  switch (shape) {
    case MarkerShape::Circle:
      cairo_new_sub_path(cr_);
      cairo_arc(cr_, c.x, c.y, r, 0.0, 2.0 * std::numbers::pi);
      break;
    case MarkerShape::Square: {
      const double s = r * 0.85;
      cairo_rectangle(cr_, c.x - s, c.y - s, 2.0 * s, 2.0 * s);
      break;
    }
    case MarkerShape::Diamond: {
      const double s = r * 1.15;
      cairo_move_to(cr_, c.x, c.y - s);
      cairo_line_to(cr_, c.x + s, c.y);
      cairo_line_to(cr_, c.x, c.y + s);
      cairo_line_to(cr_, c.x - s, c.y);
      cairo_close_path(cr_);
      break;
    }
    case MarkerShape::TriangleUp:
    case MarkerShape::TriangleDown: {
      const double s = r * 1.2, d = shape == MarkerShape::TriangleUp ? 1.0 : -1.0;
      cairo_move_to(cr_, c.x, c.y - d * s);
      cairo_line_to(cr_, c.x + 0.87 * s, c.y + d * 0.5 * s);
      cairo_line_to(cr_, c.x - 0.87 * s, c.y + d * 0.5 * s);
      cairo_close_path(cr_);
      break;
    }
  }
  set_color(cr_, fill);
  cairo_fill_preserve(cr_);
  set_color(cr_, outline);
  cairo_set_line_width(cr_, std::max(0.8, r * 0.2));
  cairo_stroke(cr_);
}

void Canvas::ring(Point2 c, double radius, double line_width, Rgb color) {
  cairo_new_sub_path(cr_);
  cairo_arc(cr_, c.x, c.y, radius, 0.0, 2.0 * std::numbers::pi);
  set_color(cr_, color);
  cairo_set_line_width(cr_, line_width);
  cairo_stroke(cr_);
}

void Canvas::triangles(const std::vector<Point2>& nodes,
                       const std::vector<std::array<int, 3>>& tris,
                       const std::vector<Rgb>& colors) {
  // Each triangle is filled and also stroked with a hairline of its own colour, which
  // covers the faint seam antialiasing leaves between two neighbours.
  cairo_set_line_width(cr_, 0.6);
  for (size_t t = 0; t < std::min(tris.size(), colors.size()); ++t) {
    const auto& tri = tris[t];
    cairo_move_to(cr_, nodes[tri[0]].x, nodes[tri[0]].y);
    cairo_line_to(cr_, nodes[tri[1]].x, nodes[tri[1]].y);
    cairo_line_to(cr_, nodes[tri[2]].x, nodes[tri[2]].y);
    cairo_close_path(cr_);
    set_color(cr_, colors[t]);
    cairo_fill_preserve(cr_);
    cairo_stroke(cr_);
  }
}

void Canvas::text(const std::string& utf8, double x, double y, double size, Rgb color, Align align,
                  bool vertical) {
  if (utf8.empty()) return;
  const double w = measured_width(cr_, utf8, size);
  cairo_font_extents_t fe;
  cairo_font_extents(cr_, &fe);
  const double shift = align == Align::Left ? 0.0 : align == Align::Center ? -w / 2.0 : -w;
  cairo_save(cr_);
  cairo_translate(cr_, x, y);
  if (vertical) cairo_rotate(cr_, -std::numbers::pi / 2.0);
  cairo_move_to(cr_, shift, 0.0);
  set_color(cr_, color);
  cairo_show_text(cr_, utf8.c_str());
  // The box from the pen's left to right and from the ascent to the descent, in drawing
  // coordinates.
  double xs[4] = {shift, shift + w, shift, shift + w},
         ys[4] = {-fe.ascent, -fe.ascent, fe.descent, fe.descent};
  TextItem item{utf8, INFINITY, INFINITY, -INFINITY, -INFINITY};
  for (int i = 0; i < 4; ++i) {
    cairo_user_to_device(cr_, &xs[i], &ys[i]);
    item.x0 = std::min(item.x0, xs[i]);
    item.x1 = std::max(item.x1, xs[i]);
    item.y0 = std::min(item.y0, ys[i]);
    item.y1 = std::max(item.y1, ys[i]);
  }
  texts_.push_back(item);
  cairo_restore(cr_);
}

void Canvas::push() {
  cairo_save(cr_);
}
void Canvas::pop() {
  cairo_restore(cr_);
}
void Canvas::clip(double x0, double y0, double x1, double y1) {
  cairo_rectangle(cr_, x0, y0, x1 - x0, y1 - y0);
  cairo_clip(cr_);
}
void Canvas::translate(double dx, double dy) {
  cairo_translate(cr_, dx, dy);
}

std::string Canvas::finish() {
  if (format_ == ChartFormat::Png) {
    std::string png;
    cairo_surface_flush(surface_);
    if (cairo_surface_write_to_png_stream(surface_, append_bytes, &png) != CAIRO_STATUS_SUCCESS)
      return "";
    return png;
  }
  cairo_surface_finish(surface_);
  if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS) return "";
  return vector_bytes_;
}

std::string write_canvas(const std::string& path, Canvas& canvas) {
  const std::string bytes = canvas.finish();
  if (bytes.empty()) return path + ": the chart could not be encoded";
  return write_file_atomically(path, bytes);
}

}  // namespace invfree
