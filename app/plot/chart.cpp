#include "app/plot/chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/plot/axis.h"
#include "app/plot/raster.h"

namespace invfree {

namespace {

constexpr Rgb kWhite{1.0f, 1.0f, 1.0f};
constexpr Rgb kInk{0.10f, 0.10f, 0.12f};
constexpr Rgb kMuted{0.35f, 0.35f, 0.38f};
constexpr Rgb kGridMajor{0.85f, 0.85f, 0.87f};
constexpr Rgb kGridMinor{0.94f, 0.94f, 0.95f};

MarkerShape marker_for(size_t index) {
  static constexpr MarkerShape shapes[] = {MarkerShape::Circle, MarkerShape::Square,
                                           MarkerShape::Diamond, MarkerShape::TriangleUp,
                                           MarkerShape::TriangleDown};
  return shapes[index % 5];
}

// "10" with a superscript exponent; returns its width. Draws only when `image` is set.
double power_of_ten_label(Image* image, int exponent, double x, double y, double size,
                          Align align) {
  const std::string base = "10";
  const std::string exp = (exponent < 0 ? "\u2212" : "") + std::to_string(std::abs(exponent));
  const double small = size * 0.72;
  const double w = text_width(base, size) + text_width(exp, small) + size * 0.05;
  if (image) {
    const double left = align == Align::Left ? x : align == Align::Center ? x - w / 2.0 : x - w;
    draw_text(*image, base, left, y, size, kInk);
    draw_text(*image, exp, left + text_width(base, size) + size * 0.05, y - size * 0.42, small,
              kInk);
  }
  return w;
}

double tick_label(Image* image, const Tick& t, double x, double y, double size, Align align) {
  if (t.decade_label) return power_of_ten_label(image, t.exponent, x, y, size, align);
  if (image) draw_text(*image, t.label, x, y, size, kInk, align);
  return text_width(t.label, size);
}

// Where a chart's parts go (pixels) and how large its text is, all scaled by u with the
// image (designed at 1280x800).
struct ChartLayout {
  int width = 0, height = 0;
  double u = 1.0, title_size = 0, label_size = 0, tick_size = 0, legend_size = 0;
  std::vector<std::string> title_lines;
  bool has_legend = false;
  PlotFrame frame;  // the plot area and the axes' ranges
  std::vector<Tick> xticks, yticks;
};

// Axes from the data; title on top, the legend and notes in a column on the right.
ChartLayout chart_layout(const ChartSpec& spec, int width, int height) {
  ChartLayout c;
  c.width = width;
  c.height = height;
  const double u = c.u = std::clamp(std::min(width / 1280.0, height / 800.0), 0.4, 4.0);
  c.title_size = 26 * u, c.label_size = 19 * u, c.tick_size = 16 * u, c.legend_size = 16 * u;
  std::vector<double> xs, ys;
  for (const Series& s : spec.series)
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      xs.push_back(s.x[i]);
      ys.push_back(s.y[i]);
    }
  const AxisRange xr = axis_range(xs, spec.log_x), yr = axis_range(ys, spec.log_y);
  c.xticks = axis_ticks(xr);
  c.yticks = axis_ticks(yr);
  c.has_legend = !spec.notes.empty();
  for (const Series& s : spec.series) c.has_legend = c.has_legend || !s.label.empty();
  const double legend_w = c.has_legend ? std::clamp(width * 0.25, 160.0 * u, 400.0 * u) : 0.0;
  double y_tick_w = 0.0;
  for (const Tick& t : c.yticks)
    if (t.labelled)
      y_tick_w = std::max(y_tick_w, tick_label(nullptr, t, 0, 0, c.tick_size, Align::Right));
  c.title_lines = wrap_text(spec.title, c.title_size, width - 40 * u);
  const double top = 24 * u + c.title_lines.size() * c.title_size * 1.2 + 12 * u;
  const double left = 24 * u + c.label_size * 1.4 + y_tick_w + 12 * u;
  const double right = width - legend_w - 30 * u;
  const double bottom = height - (20 * u + c.label_size * 1.4 + c.tick_size * 1.6 + 10 * u);
  c.frame = PlotFrame{left, top, right, bottom, xr, yr};
  return c;
}

// The title, the grid, then the frame, the ticks with their labels and the axis labels.
void draw_axes(Image& img, const ChartSpec& spec, const ChartLayout& c) {
  const double u = c.u, tick_size = c.tick_size, label_size = c.label_size;
  const PlotFrame& frame = c.frame;
  const double left = frame.left, top = frame.top, right = frame.right, bottom = frame.bottom;
  for (size_t i = 0; i < c.title_lines.size(); ++i)
    draw_text(img, c.title_lines[i], c.width / 2.0, 24 * u + c.title_size * (1.2 * i + 0.85),
              c.title_size, kInk, Align::Center);
  for (const Tick& t : c.xticks) {
    const double px = frame.to_px_x(t.value);
    draw_line(img, {px, top}, {px, bottom}, 1.0, t.major ? kGridMajor : kGridMinor);
  }
  for (const Tick& t : c.yticks) {
    const double py = frame.to_px_y(t.value);
    draw_line(img, {left, py}, {right, py}, 1.0, t.major ? kGridMajor : kGridMinor);
  }
  stroke_rect(img, left, top, right, bottom, 1.2 * u, kInk);
  for (const Tick& t : c.xticks) {
    const double px = frame.to_px_x(t.value);
    const double len = (t.major ? 8.0 : 4.5) * u;
    draw_line(img, {px, bottom}, {px, bottom + len}, 1.2 * u, kInk);
    if (t.labelled)
      tick_label(&img, t, px, bottom + len + tick_size * 1.05, tick_size, Align::Center);
  }
  for (const Tick& t : c.yticks) {
    const double py = frame.to_px_y(t.value);
    const double len = (t.major ? 8.0 : 4.5) * u;
    draw_line(img, {left - len, py}, {left, py}, 1.2 * u, kInk);
    if (t.labelled)
      tick_label(&img, t, left - len - 4 * u, py + tick_size * 0.35, tick_size, Align::Right);
  }
  draw_text(img, spec.x_label, (left + right) / 2.0, c.height - 20 * u, label_size, kInk,
            Align::Center);
  draw_text_vertical(img, spec.y_label, 20 * u + label_size, (top + bottom) / 2.0, label_size,
                     kInk);
}

double line_width(const ChartLayout& c) {
  return 2.2 * c.u;
}
double marker_radius(const ChartLayout& c) {
  return 5.0 * c.u;
}

// Lines first (broken at skipped points), then markers on top.
void draw_series(Image& img, const ChartSpec& spec, const ChartLayout& c) {
  const PlotFrame& frame = c.frame;
  for (const Series& s : spec.series) {
    if (!s.lines) continue;
    std::vector<Point2> run;
    for (size_t i = 0; i <= std::min(s.x.size(), s.y.size()); ++i) {
      const bool end = i == std::min(s.x.size(), s.y.size());
      if (!end && frame.plottable(s.x[i], s.y[i])) {
        run.push_back({frame.to_px_x(s.x[i]), frame.to_px_y(s.y[i])});
        continue;
      }
      if (run.size() >= 2) draw_polyline(img, run, line_width(c), s.color);
      run.clear();
    }
  }
  for (size_t k = 0; k < spec.series.size(); ++k) {
    const Series& s = spec.series[k];
    if (!s.markers) continue;
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
      if (frame.plottable(s.x[i], s.y[i]))
        draw_marker(img, {frame.to_px_x(s.x[i]), frame.to_px_y(s.y[i])}, marker_radius(c),
                    marker_for(k), s.color, kInk);
  }
}

// The legend (a swatch and the label per labelled series), then the notes, word-wrapped.
void draw_legend(Image& img, const ChartSpec& spec, const ChartLayout& c) {
  const double u = c.u, legend_size = c.legend_size;
  const double lx = c.frame.right + 24 * u, lw = c.width - lx - 16 * u;
  double ly = c.frame.top + legend_size;
  const double swatch = 34 * u;
  for (size_t k = 0; k < spec.series.size(); ++k) {
    const Series& s = spec.series[k];
    if (s.label.empty()) continue;
    const auto lines = wrap_text(s.label, legend_size, lw - swatch - 10 * u);
    const double cy = ly - legend_size * 0.35;
    if (s.lines) draw_line(img, {lx, cy}, {lx + swatch, cy}, line_width(c), s.color);
    if (s.markers)
      draw_marker(img, {lx + swatch / 2.0, cy}, marker_radius(c), marker_for(k), s.color, kInk);
    for (size_t i = 0; i < lines.size(); ++i)
      draw_text(img, lines[i], lx + swatch + 10 * u, ly + i * legend_size * 1.25, legend_size,
                kInk);
    ly += (lines.size() * 1.25 + 0.6) * legend_size;
  }
  if (!spec.notes.empty()) ly += legend_size * 0.8;
  const double note_size = legend_size * 0.92;
  for (const std::string& note : spec.notes) {
    for (const std::string& line : wrap_text(note, note_size, lw)) {
      draw_text(img, line, lx, ly, note_size, kMuted);
      ly += note_size * 1.3;
    }
    ly += note_size * 0.5;
  }
}

}  // namespace

Image render_chart(const ChartSpec& spec) {
  const int width = std::max(spec.width, 160), height = std::max(spec.height, 120);
  Image img = make_image(width, height, kWhite);
  const ChartLayout layout = chart_layout(spec, width, height);
  draw_axes(img, spec, layout);
  draw_series(img, spec, layout);
  if (layout.has_legend) draw_legend(img, spec, layout);
  return img;
}

}  // namespace invfree
