#include "app/plot/chart.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "app/plot/axis.h"

namespace invfree {

namespace {

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

// "10" with a superscript exponent; returns its width. Draws only when `canvas` is set.
double power_of_ten_label(Canvas* canvas, int exponent, double x, double y, double size,
                          Align align) {
  const std::string base = "10";
  const std::string exp = (exponent < 0 ? "\u2212" : "") + std::to_string(std::abs(exponent));
  const double small = size * 0.72;
  const double w = text_width(base, size) + text_width(exp, small) + size * 0.05;
  if (canvas) {
    const double left = align == Align::Left ? x : align == Align::Center ? x - w / 2.0 : x - w;
    canvas->text(base, left, y, size, kInk);
    canvas->text(exp, left + text_width(base, size) + size * 0.05, y - size * 0.42, small, kInk);
  }
  return w;
}

double tick_label(Canvas* canvas, const Tick& t, double x, double y, double size, Align align) {
  if (t.decade_label) return power_of_ten_label(canvas, t.exponent, x, y, size, align);
  if (canvas) canvas->text(t.label, x, y, size, kInk, align);
  return text_width(t.label, size);
}

// Where a chart's parts go and how large its text is, all scaled by u with the chart
// (designed at 1280 x 800).
struct ChartLayout {
  double width = 0, height = 0;  // the plot's part
  double u = 1.0, title_size = 0, label_size = 0, tick_size = 0, legend_size = 0, note_size = 0;
  std::vector<std::string> title_lines;
  struct LegendEntry {
    size_t series;
    std::vector<std::string> lines;
    double baseline;
  };
  std::vector<LegendEntry> legend;
  double legend_x = 0;
  std::vector<std::vector<std::string>> notes;  // wrapped lines per paragraph
  double notes_top = 0, total_height = 0;
  PlotFrame frame;  // the plot area and the axes' ranges
  std::vector<Tick> xticks, yticks;
};

// Axes from the data; the title on top, the legend in a column on the right, the notes
// below everything.
ChartLayout chart_layout(const ChartSpec& spec) {
  ChartLayout c;
  c.width = std::max(spec.width, 160);
  c.height = std::max(spec.height, 120);
  const double u = c.u = std::clamp(std::min(c.width / 1280.0, c.height / 800.0), 0.4, 4.0) *
                         std::clamp(spec.type_scale, 0.25, 4.0);
  c.title_size = 26 * u, c.label_size = 19 * u, c.tick_size = 16 * u, c.legend_size = 16 * u;
  c.note_size = 15 * u;
  std::vector<double> xs, ys;
  for (const Series& s : spec.series)
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      xs.push_back(s.x[i]);
      ys.push_back(s.y[i]);
    }
  xs.insert(xs.end(), spec.x_ticks.begin(), spec.x_ticks.end());  // every given tick shows
  ys.insert(ys.end(), spec.y_ticks.begin(), spec.y_ticks.end());
  const AxisRange xr = axis_range(xs, spec.log_x), yr = axis_range(ys, spec.log_y);
  c.xticks = spec.x_ticks.empty() ? axis_ticks(xr) : value_ticks(spec.x_ticks, xr);
  c.yticks = spec.y_ticks.empty() ? axis_ticks(yr) : value_ticks(spec.y_ticks, yr);
  bool has_legend = false;
  for (const Series& s : spec.series) has_legend = has_legend || !s.label.empty();
  const double legend_w = has_legend ? std::clamp(c.width * 0.25, 160.0 * u, 400.0 * u) : 0.0;
  double y_tick_w = 0.0;
  for (const Tick& t : c.yticks)
    if (t.labelled)
      y_tick_w = std::max(y_tick_w, tick_label(nullptr, t, 0, 0, c.tick_size, Align::Right));
  c.title_lines = wrap_text(spec.title, c.title_size, c.width - 40 * u);
  const double top = 24 * u + c.title_lines.size() * c.title_size * 1.2 + 12 * u;
  const double left = 24 * u + c.label_size * 1.4 + y_tick_w + 12 * u;
  const double right = c.width - legend_w - 30 * u;
  const double bottom = c.height - (20 * u + c.label_size * 1.4 + c.tick_size * 1.6 + 10 * u);
  c.frame = PlotFrame{left, top, right, bottom, xr, yr};

  c.legend_x = right + 24 * u;
  const double swatch = 34 * u, text_w = c.width - c.legend_x - 16 * u - swatch - 10 * u;
  double ly = top + c.legend_size;
  for (size_t k = 0; k < spec.series.size(); ++k) {
    if (spec.series[k].label.empty()) continue;
    c.legend.push_back({k, wrap_text(spec.series[k].label, c.legend_size, text_w), ly});
    ly += (c.legend.back().lines.size() * 1.25 + 0.6) * c.legend_size;
  }
  c.notes_top = std::max(c.height, ly) + 4 * u;
  double ny = c.notes_top;
  for (const std::string& note : spec.notes) {
    c.notes.push_back(wrap_text(note, c.note_size, c.width - 48 * u));
    ny += (c.notes.back().size() * 1.3 + 0.5) * c.note_size;
  }
  c.total_height = std::ceil(spec.notes.empty() ? std::max(c.height, ly) : ny + 12 * u);
  return c;
}

// The title, the grid, then the frame, the ticks with their labels and the axis labels.
void draw_axes(Canvas& cv, const ChartSpec& spec, const ChartLayout& c) {
  const double u = c.u, tick_size = c.tick_size, label_size = c.label_size;
  const PlotFrame& frame = c.frame;
  const double left = frame.left, top = frame.top, right = frame.right, bottom = frame.bottom;
  for (size_t i = 0; i < c.title_lines.size(); ++i)
    cv.text(c.title_lines[i], c.width / 2.0, 24 * u + c.title_size * (1.2 * i + 0.85), c.title_size,
            kInk, Align::Center);
  for (const Tick& t : c.xticks) {
    const double px = frame.to_px_x(t.value);
    cv.line({px, top}, {px, bottom}, 1.0, t.major ? kGridMajor : kGridMinor);
  }
  for (const Tick& t : c.yticks) {
    const double py = frame.to_px_y(t.value);
    cv.line({left, py}, {right, py}, 1.0, t.major ? kGridMajor : kGridMinor);
  }
  cv.stroke_rect(left, top, right, bottom, 1.2 * u, kInk);
  for (const Tick& t : c.xticks) {
    const double px = frame.to_px_x(t.value);
    const double len = (t.major ? 8.0 : 4.5) * u;
    cv.line({px, bottom}, {px, bottom + len}, 1.2 * u, kInk);
    if (t.labelled)
      tick_label(&cv, t, px, bottom + len + tick_size * 1.05, tick_size, Align::Center);
  }
  for (const Tick& t : c.yticks) {
    const double py = frame.to_px_y(t.value);
    const double len = (t.major ? 8.0 : 4.5) * u;
    cv.line({left - len, py}, {left, py}, 1.2 * u, kInk);
    if (t.labelled)
      tick_label(&cv, t, left - len - 4 * u, py + tick_size * 0.35, tick_size, Align::Right);
  }
  cv.text(spec.x_label, (left + right) / 2.0, c.height - 20 * u, label_size, kInk, Align::Center);
  cv.text(spec.y_label, 20 * u + label_size, (top + bottom) / 2.0, label_size, kInk, Align::Center,
          true);
}

double line_width(const ChartLayout& c) {
  return 2.2 * c.u;
}
double marker_radius(const ChartLayout& c) {
  return 5.0 * c.u;
}

// Lines first (broken at skipped points, clipped to the plot), then markers and their
// labels on top.
void draw_series(Canvas& cv, const ChartSpec& spec, const ChartLayout& c) {
  const PlotFrame& frame = c.frame;
  cv.push();
  cv.clip(frame.left, frame.top, frame.right, frame.bottom);
  for (const Series& s : spec.series) {
    if (!s.lines) continue;
    std::vector<Point2> run;
    for (size_t i = 0; i <= std::min(s.x.size(), s.y.size()); ++i) {
      const bool end = i == std::min(s.x.size(), s.y.size());
      if (!end && frame.plottable(s.x[i], s.y[i])) {
        run.push_back({frame.to_px_x(s.x[i]), frame.to_px_y(s.y[i])});
        continue;
      }
      cv.polyline(run, line_width(c), s.color, 1.0, s.dash * c.u);
      run.clear();
    }
  }
  cv.pop();
  // Point labels go above-right of their point, or below-right when that would overlap a
  // label already placed; a label that overlaps either way is left out.
  std::vector<std::array<double, 4>> placed;
  const double label_size = 12 * c.u, r = marker_radius(c);
  auto place_label = [&](const std::string& text, Point2 p) {
    if (text.empty()) return;
    const double w = text_width(text, label_size);
    for (double baseline : {p.y - 1.2 * r, p.y + 1.2 * r + label_size * 0.8}) {
      const std::array<double, 4> box{p.x + 1.6 * r, baseline - label_size * 0.8, p.x + 1.6 * r + w,
                                      baseline + label_size * 0.2};
      const bool overlaps = std::any_of(placed.begin(), placed.end(), [&](const auto& b) {
        return box[0] < b[2] && b[0] < box[2] && box[1] < b[3] && b[1] < box[3];
      });
      if (overlaps) continue;
      placed.push_back(box);
      cv.text(text, box[0], baseline, label_size, kMuted);
      return;
    }
  };
  for (size_t k = 0; k < spec.series.size(); ++k) {
    const Series& s = spec.series[k];
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!frame.plottable(s.x[i], s.y[i])) continue;
      const Point2 p{frame.to_px_x(s.x[i]), frame.to_px_y(s.y[i])};
      if (s.markers) cv.marker(p, r, marker_for(k), s.color, kInk);
      if (i < s.point_labels.size()) place_label(s.point_labels[i], p);
    }
  }
}

// The legend (a swatch and the label per labelled series), then the notes.
void draw_legend_and_notes(Canvas& cv, const ChartSpec& spec, const ChartLayout& c) {
  const double u = c.u, swatch = 34 * u, lx = c.legend_x;
  for (const ChartLayout::LegendEntry& e : c.legend) {
    const Series& s = spec.series[e.series];
    const double cy = e.baseline - c.legend_size * 0.35;
    if (s.lines)
      cv.polyline({{lx, cy}, {lx + swatch, cy}}, line_width(c), s.color, 1.0, s.dash * u * 0.5);
    if (s.markers)
      cv.marker({lx + swatch / 2.0, cy}, marker_radius(c), marker_for(e.series), s.color, kInk);
    for (size_t i = 0; i < e.lines.size(); ++i)
      cv.text(e.lines[i], lx + swatch + 10 * u, e.baseline + i * c.legend_size * 1.25,
              c.legend_size, kInk);
  }
  double ny = c.notes_top + c.note_size;
  for (const auto& lines : c.notes) {
    for (const std::string& line : lines) {
      cv.text(line, 24 * u, ny, c.note_size, kMuted);
      ny += c.note_size * 1.3;
    }
    ny += c.note_size * 0.5;
  }
}

}  // namespace

double chart_height(const ChartSpec& spec) {
  return chart_layout(spec).total_height;
}

void draw_chart(Canvas& canvas, const ChartSpec& spec) {
  const ChartLayout layout = chart_layout(spec);
  draw_axes(canvas, spec, layout);
  draw_series(canvas, spec, layout);
  draw_legend_and_notes(canvas, spec, layout);
}

std::unique_ptr<Canvas> chart_canvas(const std::vector<ChartSpec>& panels, ChartFormat format) {
  double width = 0.0, height = 0.0;
  for (const ChartSpec& p : panels) {
    width = std::max(width, double(std::max(p.width, 160)));
    height += chart_height(p);
  }
  auto canvas = std::make_unique<Canvas>(width, height, format);
  double y = 0.0;
  for (const ChartSpec& p : panels) {
    canvas->push();
    canvas->translate(0.0, y);
    draw_chart(*canvas, p);
    canvas->pop();
    y += chart_height(p);
  }
  return canvas;
}

}  // namespace invfree
