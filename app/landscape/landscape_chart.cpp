#include "app/landscape/landscape_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "app/format_number.h"

namespace invfree {

namespace {

constexpr Rgb kInk{0.10f, 0.10f, 0.12f};
constexpr Rgb kMuted{0.35f, 0.35f, 0.38f};
constexpr Rgb kWhite{1.0f, 1.0f, 1.0f};
constexpr Rgb kDot{0.05f, 0.33f, 0.95f};
constexpr Rgb kPinned{0.70f, 0.80f, 1.0f};

// Sizes in points (one pixel of a PNG). The heat map is drawn in cells of kCellPx: a cell's
// colour is Psi at its centre, so the picture is exact to a cell, and the contours come from
// a finer grid (kContourPerUnit nodes per unit of sigma).
constexpr double kCellPx = 2.0;
constexpr int kContourPerUnit = 100;
constexpr double kLeft = 70.0, kGap = 64.0, kRight = 150.0;
constexpr double kTitleSize = 16.0, kCaptionSize = 12.0, kSubtitleSize = 14.0, kSmall = 11.0;
constexpr double kTickSize = 11.0, kAxisLabelSize = 15.0, kNoteSize = 11.0;
// The heat map's colours are quantised to steps along the scale so that a row's equal
// neighbours merge into one rectangle: in a PNG finer than the eye separates; in a vector
// file (a rectangle is an element there) 16 a decade on cells twice as large, which keeps an
// SVG of four panels near a megabyte.
constexpr int kPngColorSteps = 128, kVectorColorSteps = 48;

struct Layout {
  LandscapeDomain domain;
  int cells_per_unit = 0;
  double ppu = 0;  // points per unit of sigma
  double plot_w = 0, plot_h = 0;
  double top = 0;    // the plots' top edge
  double bar_x = 0;  // the colour bar's left edge
  double width = 0;  // the drawing's
  double legend_top = 0, notes_top = 0, height = 0;
  std::vector<std::string> title_lines, caption_lines;
  std::vector<std::vector<std::string>> notes;
  double plot_left(size_t panel) const { return kLeft + panel * (plot_w + kGap); }
};

struct PanelMap {
  double x0, y0, ppu;
  LandscapeDomain d;
  double x(double s1) const { return x0 + (s1 - d.s1_min) * ppu; }
  double y(double s2) const { return y0 + (d.s2_max - s2) * ppu; }
};

bool inside_domain(const LandscapeDomain& d, const SigmaPair& p) {
  return p.s1 >= d.s1_min && p.s1 <= d.s1_max && p.s2 >= d.s2_min && p.s2 <= d.s2_max;
}

std::string tick_text(double v) {
  if (std::abs(v) < 1e-9) return "0";
  std::string s = format_number(std::abs(v), "%g");
  return v < 0 ? "\u2212" + s : s;
}

bool any_barrier_model(const LandscapeChartSpec& spec) {
  return std::any_of(spec.models.begin(), spec.models.end(),
                     [](Model m) { return !model_allows_inversion(m); });
}
bool any_invertible_model(const LandscapeChartSpec& spec) {
  return std::any_of(spec.models.begin(), spec.models.end(),
                     [](Model m) { return model_allows_inversion(m); });
}

std::vector<std::string> standard_notes(const LandscapeChartSpec& spec) {
  std::vector<std::string> notes;
  notes.push_back(
      "\u03a8(\u03c3\u2081, \u03c3\u2082) is the energy density at F = diag(\u03c3\u2081, "
      "\u03c3\u2082), on one logarithmic colour scale for every panel (three decades; a "
      "darker step is more energy); the contours are at 1 and 3 \u00d7 10\u207f Pa. The polar SVD "
      "orders \u03c3\u2081 \u2265 |\u03c3\u2082|, with "
      "\u03c3\u2082 < 0 for an inverted triangle, so the dots stay between the diagonals "
      "\u03c3\u2082 = \u00b1\u03c3\u2081; a rotation-invariant model's landscape is mirrored "
      "across them.");
  if (any_barrier_model(spec) && any_invertible_model(spec))
    notes.push_back(
        "Only neo-Hookean's energy goes to +\u221e as \u03c3\u2081\u03c3\u2082 = det F \u2192 0: "
        "a barrier that no finite step crosses, so its solver needs the inversion-free line "
        "search and nothing else. The others stay finite through \u03c3\u2082 = 0 and into "
        "inversion: a step may take a triangle there.");
  if (std::find(spec.models.begin(), spec.models.end(), Model::Linear) != spec.models.end())
    notes.push_back(
        "Linear elasticity is not rotation invariant: its panel is \u03a8 at U = V = I, and a "
        "rotated triangle's energy is not the value under its dot.");
  for (const std::string& n : spec.notes) notes.push_back(n);
  return notes;
}

struct LegendItem {
  enum Kind { Dot, Pinned, Contour, Wall, Dashed, Rest } kind;
  std::string text;
};

std::vector<LegendItem> legend_items(const LandscapeChartSpec& spec) {
  std::vector<LegendItem> items;
  if (!spec.points.empty())
    items.push_back({LegendItem::Dot, "a triangle's (\u03c3\u2081, \u03c3\u2082) now"});
  const LandscapeDomain d = chart_domain(spec);
  if (std::any_of(spec.points.begin(), spec.points.end(),
                  [&](const SigmaPair& p) { return !inside_domain(d, p); }))
    items.push_back({LegendItem::Pinned, "a triangle beyond the drawn domain, pinned to its edge"});
  items.push_back({LegendItem::Contour, "contour of \u03a8 (its level: a tick of the colour bar)"});
  if (any_barrier_model(spec))
    items.push_back({LegendItem::Wall,
                     "\u03c3\u2081\u03c3\u2082 = 0: neo-Hookean's wall, \u03a8 = +\u221e on "
                     "and beyond it (hatched)"});
  if (any_invertible_model(spec))
    items.push_back({LegendItem::Dashed, "\u03c3\u2082 = 0 (det F = 0) where \u03a8 stays finite"});
  items.push_back(
      {LegendItem::Rest, "rest: \u03c3\u2081 = \u03c3\u2082 = 1 (F a rotation), \u03a8 = 0"});
  return items;
}

constexpr double kLegendLine = 19.0;

Layout layout(const LandscapeChartSpec& spec) {
  Layout l;
  l.domain = chart_domain(spec);
  const double h_units = l.domain.s2_max - l.domain.s2_min;
  const double w_units = l.domain.s1_max - l.domain.s1_min;
  l.cells_per_unit =
      std::max(1, static_cast<int>(std::floor(spec.plot_height / kCellPx / h_units)));
  l.ppu = l.cells_per_unit * kCellPx;
  l.plot_w = w_units * l.ppu;
  l.plot_h = h_units * l.ppu;
  const size_t n = std::max<size_t>(spec.models.size(), 1);
  l.bar_x = l.plot_left(n - 1) + l.plot_w + 36.0;
  l.width = l.bar_x + kRight;
  const std::string title =
      "Energy density \u03a8(\u03c3\u2081, \u03c3\u2082) of " +
      (spec.models.size() == 1 ? std::string(model_label(spec.models[0]))
                               : std::to_string(spec.models.size()) + " models") +
      ":  \u03bc = " + format_pascal(spec.lame.mu) +
      ",  \u03bb = " + format_pascal(spec.lame.lambda);
  l.title_lines = wrap_text(title, kTitleSize, l.width - 2 * 16.0);
  double y = 12.0 + l.title_lines.size() * kTitleSize * 1.3;
  if (!spec.points_caption.empty())
    l.caption_lines = wrap_text(spec.points_caption, kCaptionSize, l.width - 2 * 16.0);
  y += l.caption_lines.size() * kCaptionSize * 1.5;
  l.top = y + 50.0;  // the panels' two subtitle lines
  const double plots_bottom = l.top + l.plot_h;
  // Below the plots: tick labels, the axis label, the forbidden swatch beside the bar.
  l.legend_top = plots_bottom + 62.0;
  l.notes_top = l.legend_top + legend_items(spec).size() * kLegendLine + 10.0;
  double notes_h = 0;
  for (const std::string& p : standard_notes(spec)) {
    l.notes.push_back(wrap_text(p, kNoteSize, l.width - kLeft - 24.0));
    notes_h += l.notes.back().size() * kNoteSize * 1.35 + 6.0;
  }
  l.height = std::ceil(l.notes_top + notes_h + 10.0);
  l.width = std::ceil(l.width);
  return l;
}

// Diagonal hatching over a rectangle (the forbidden region, and its swatch).
void hatch(Canvas& c, double x0, double y0, double x1, double y1) {
  c.push();
  c.clip(x0, y0, x1, y1);
  const double step = 9.0;
  for (double k = x0 - (y1 - y0); k < x1; k += step)
    c.line({k, y1}, {k + (y1 - y0), y0}, 1.0, kWhite, 0.45);
  c.pop();
}

// The heat map: rows of cells, each row's equal neighbours merged into one rectangle. Each
// rectangle reaches half a point into the next row and column, which are drawn after it and
// cover that (so a PNG has no antialiased seam and a vector viewer none either); the plot
// clip cuts the overhang of the last ones.
void heat_map(Canvas& c, const PanelMap& m, const Layout& l, Model model, const Lame& lame,
              const LandscapeScale& scale, bool vector) {
  const int per_unit = vector ? std::max(1, l.cells_per_unit / 2) : l.cells_per_unit;
  const int steps = vector ? kVectorColorSteps : kPngColorSteps;
  const int cols = static_cast<int>(std::lround((l.domain.s1_max - l.domain.s1_min) * per_unit));
  const int rows = static_cast<int>(std::lround((l.domain.s2_max - l.domain.s2_min) * per_unit));
  const double cell = 1.0 / per_unit, cell_px = l.ppu / per_unit;
  std::vector<int> q(static_cast<size_t>(cols));
  c.push();
  c.clip(m.x(l.domain.s1_min), m.y(l.domain.s2_max), m.x(l.domain.s1_max), m.y(l.domain.s2_min));
  for (int r = 0; r < rows; ++r) {
    const double s2 = l.domain.s2_max - (r + 0.5) * cell;
    for (int k = 0; k < cols; ++k) {
      const double t = landscape_scale_position(
          scale, landscape_psi(model, lame, l.domain.s1_min + (k + 0.5) * cell, s2));
      q[static_cast<size_t>(k)] = std::isnan(t) ? -1 : static_cast<int>(std::lround(t * steps));
    }
    const double y0 = m.y0 + r * cell_px;
    for (int k = 0; k < cols;) {
      int e = k + 1;
      while (e < cols && q[static_cast<size_t>(e)] == q[static_cast<size_t>(k)]) ++e;
      const int v = q[static_cast<size_t>(k)];
      const Rgb color = v < 0 ? kForbiddenColor : landscape_scale_color(double(v) / steps);
      c.fill_rect(m.x0 + k * cell_px, y0, m.x0 + e * cell_px + 0.5, y0 + cell_px + 0.5, color);
      k = e;
    }
  }
  c.pop();
}

struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// Labels the contours where they fit: each level at the point of its lines whose direction
// from the rest point is closest to one of a few preferred directions (up and right first,
// where every model's bowl opens), skipping a place that would leave the plot or cover
// another label.
void contour_labels(Canvas& c, const PanelMap& m, const std::vector<ContourLine>& lines,
                    const std::vector<double>& levels, std::vector<Box> taken) {
  static constexpr double kAngles[] = {45.0, 25.0, 65.0, -20.0, 110.0, 150.0, -60.0};
  const double rest_x = m.x(1.0), rest_y = m.y(1.0);
  const Box plot{m.x(m.d.s1_min) + 2, m.y(m.d.s2_max) + 2, m.x(m.d.s1_max) - 2,
                 m.y(m.d.s2_min) - 2};
  for (double level : levels) {
    const std::string text = format_pascal(level);
    const double w = text_width(text, 10.0) + 6.0, h = 14.0;
    bool placed = false;
    for (double angle : kAngles) {
      const double ux = std::cos(angle * std::numbers::pi / 180.0),
                   uy = -std::sin(angle * std::numbers::pi / 180.0);
      double best = -0.9;  // cosine of the angle to the preferred direction; at least 25 deg
      double bx = 0, by = 0;
      for (const ContourLine& line : lines) {
        if (line.level != level) continue;
        for (const SigmaPair& p : line.points) {
          const double dx = m.x(p.s1) - rest_x, dy = m.y(p.s2) - rest_y;
          const double r = std::hypot(dx, dy);
          if (r < 12.0) continue;
          const double cosine = (dx * ux + dy * uy) / r;
          if (cosine > best && cosine > 0.9) {
            best = cosine;
            bx = m.x(p.s1);
            by = m.y(p.s2);
          }
        }
      }
      if (best < 0.9) continue;
      const Box b{bx - w / 2, by - h / 2, bx + w / 2, by + h / 2};
      if (b.x0 < plot.x0 || b.x1 > plot.x1 || b.y0 < plot.y0 || b.y1 > plot.y1) continue;
      if (std::any_of(taken.begin(), taken.end(), [&](const Box& o) { return o.overlaps(b); }))
        continue;
      c.fill_rect(b.x0, b.y0, b.x1, b.y1, kWhite, 0.8);
      c.text(text, bx, by + 3.6, 10.0, kInk, Align::Center);
      taken.push_back(b);
      placed = true;
      break;
    }
    (void)placed;  // a level with no room keeps its tick on the colour bar
  }
}

void panel(Canvas& c, const Layout& l, size_t index, Model model, const LandscapeChartSpec& spec,
           const LandscapeScale& scale, const std::vector<double>& levels, bool vector) {
  const PanelMap m{l.plot_left(index), l.top, l.ppu, l.domain};
  const LandscapeDomain& d = l.domain;
  const double X0 = m.x(d.s1_min), X1 = m.x(d.s1_max), Y0 = m.y(d.s2_max), Y1 = m.y(d.s2_min);
  const bool barrier = !model_allows_inversion(model);

  c.text(model_label(model), X0, Y0 - 28.0, kSubtitleSize, kInk);
  const std::string sub =
      barrier ? "barrier: \u03a8 \u2192 +\u221e as \u03c3\u2081\u03c3\u2082 \u2192 0"
      : model == Model::Linear ? "finite at \u03c3\u2082 = 0 (U = V = I)"
                               : "finite at \u03c3\u2082 = 0: may invert";
  c.text(sub, X0, Y0 - 10.0, kSmall, kMuted);

  heat_map(c, m, l, model, spec.lame, scale, vector);
  if (barrier && d.s2_min < 0.0) {
    hatch(c, X0, m.y(0.0), X1, Y1);
    const double mid = 0.5 * (m.y(0.0) + Y1);
    if (Y1 - m.y(0.0) > 30.0) {
      c.text("\u03a8 = +\u221e", 0.5 * (X0 + X1), mid - 2.0, 13.0, kWhite, Align::Center);
      c.text("det F \u2264 0: forbidden", 0.5 * (X0 + X1), mid + 14.0, kSmall, kWhite,
             Align::Center);
    }
  }

  // Contours from a finer grid than the cells.
  LandscapeGrid grid;
  build_landscape_grid(model, spec.lame, d, kContourPerUnit, &grid);
  std::vector<ContourLine> lines;
  landscape_contours(grid, levels, &lines);
  c.push();
  c.clip(X0, Y0, X1, Y1);
  std::vector<Point2> pts;
  for (const ContourLine& line : lines) {
    pts.clear();
    for (const SigmaPair& p : line.points) pts.push_back({m.x(p.s1), m.y(p.s2)});
    c.polyline(pts, 0.9, kInk, 0.6);
  }
  // The line s2 = 0 (and neo-Hookean's s1 = 0 column, the other half of s1 s2 = 0).
  if (d.s2_min < 0.0) {
    if (barrier)
      c.line({X0, m.y(0.0)}, {X1, m.y(0.0)}, 3.0, kInk);
    else
      c.polyline({{X0, m.y(0.0)}, {X1, m.y(0.0)}}, 1.4, kInk, 0.85, 6.0);
  }
  if (barrier) c.line({X0 + 1.5, Y0}, {X0 + 1.5, m.y(std::max(0.0, d.s2_min))}, 3.0, kInk);
  c.pop();
  // The line's name sits at its left end, where no triangle goes (s1 >= |s2|: a dot near
  // s2 = 0 has s1 well above it); the contour labels keep clear of it and of the rest point.
  std::vector<Box> taken = {{m.x(1.0) - 7, m.y(1.0) - 7, m.x(1.0) + 7, m.y(1.0) + 7}};
  if (d.s2_min < 0.0) {
    const std::string wall = barrier ? "\u03c3\u2081\u03c3\u2082 = 0: \u03a8 \u2192 +\u221e"
                                     : "\u03c3\u2082 = 0: det F = 0, \u03a8 finite";
    const double w = text_width(wall, kSmall);
    const Box b{X0 + 6, m.y(0.0) - 18.0, X0 + 14 + w, m.y(0.0) - 3.0};
    c.fill_rect(b.x0, b.y0, b.x1, b.y1, kWhite, 0.85);
    c.text(wall, X0 + 10.0, m.y(0.0) - 7.0, kSmall, kInk);
    taken.push_back(b);
    taken.push_back({X0, m.y(0.0) - 3.0, X1, m.y(0.0) + 3.0});  // the line itself
  }
  contour_labels(c, m, lines, levels, taken);

  // The rest point.
  c.ring({m.x(1.0), m.y(1.0)}, 4.5, 1.6, kInk);

  // The triangles, one marker per 1.5-point cell (a dot drawn on a dot adds nothing, and a
  // vector file stays small at n_seg 256).
  c.push();
  c.clip(X0 - 5, Y0 - 5, X1 + 5, Y1 + 5);
  const double bin = 1.5;
  const int bw = static_cast<int>((X1 - X0) / bin) + 3, bh = static_cast<int>((Y1 - Y0) / bin) + 3;
  std::vector<char> seen(static_cast<size_t>(bw) * bh, 0);
  // A triangle beyond the domain (a stretch past 2) is pinned to its edge as a pale diamond,
  // so a squashed body's sideways stretch is not silently missing.
  for (const SigmaPair& p : spec.points) {
    const bool inside = inside_domain(d, p);
    const double px = m.x(std::clamp(p.s1, d.s1_min, d.s1_max));
    const double py = m.y(std::clamp(p.s2, d.s2_min, d.s2_max));
    const int bx = static_cast<int>((px - X0) / bin) + 1,
              by = static_cast<int>((py - Y0) / bin) + 1;
    char& s = seen[static_cast<size_t>(bx + bw * by)];
    if (s) continue;
    s = 1;
    if (inside)
      c.marker({px, py}, 2.8, MarkerShape::Circle, kDot, kWhite);
    else
      c.marker({px, py}, 3.4, MarkerShape::Diamond, kPinned, kDot);
  }
  c.pop();

  c.stroke_rect(X0, Y0, X1, Y1, 1.0, kInk);
  // Ticks every 0.5.
  for (double v = std::ceil(d.s1_min * 2.0) / 2.0; v <= d.s1_max + 1e-9; v += 0.5) {
    c.line({m.x(v), Y1}, {m.x(v), Y1 + 4.0}, 1.0, kInk);
    c.text(tick_text(v), m.x(v), Y1 + 17.0, kTickSize, kInk, Align::Center);
  }
  for (double v = std::ceil(d.s2_min * 2.0) / 2.0; v <= d.s2_max + 1e-9; v += 0.5) {
    c.line({X0 - 4.0, m.y(v)}, {X0, m.y(v)}, 1.0, kInk);
    c.text(tick_text(v), X0 - 7.0, m.y(v) + 4.0, kTickSize, kInk, Align::Right);
  }
  c.text("\u03c3\u2081", 0.5 * (X0 + X1), Y1 + 38.0, kAxisLabelSize, kInk, Align::Center);
  c.text("\u03c3\u2082", X0 - 38.0, 0.5 * (Y0 + Y1) + 5.0, kAxisLabelSize, kInk, Align::Right);
}

void color_bar(Canvas& c, const Layout& l, const LandscapeScale& scale,
               const std::vector<double>& levels, bool forbidden_swatch) {
  const double x0 = l.bar_x, x1 = x0 + 18.0, y0 = l.top, y1 = l.top + l.plot_h;
  c.text("\u03a8 (Pa)", x0, y0 - 10.0, 12.0, kInk);
  const int strips = static_cast<int>(l.plot_h);
  for (int k = 0; k < strips; ++k) {
    const double t = 1.0 - (k + 0.5) / strips;
    c.fill_rect(x0, y0 + k, x1, y0 + k + 1.5, landscape_scale_color(t));
  }
  c.stroke_rect(x0, y0, x1, y1, 1.0, kInk);
  for (double level : levels) {
    const double y = y1 - landscape_scale_position(scale, level) * (y1 - y0);
    c.line({x0, y}, {x1 + 4.0, y}, 1.0, kInk, 0.8);
    c.text(format_pascal(level), x1 + 7.0, y + 4.0, kTickSize, kInk);
  }
  if (forbidden_swatch) {
    const double sy = y1 + 16.0;
    c.fill_rect(x0, sy, x1, sy + 18.0, kForbiddenColor);
    hatch(c, x0, sy, x1, sy + 18.0);
    c.stroke_rect(x0, sy, x1, sy + 18.0, 1.0, kInk);
    c.text("+\u221e (forbidden)", x1 + 7.0, sy + 13.0, kTickSize, kInk);
  }
}

void legend(Canvas& c, const Layout& l, const LandscapeChartSpec& spec) {
  double y = l.legend_top;
  const double x = kLeft, sx = x + 30.0;
  for (const LegendItem& item : legend_items(spec)) {
    const double cy = y - 4.0;
    switch (item.kind) {
      case LegendItem::Dot:
        c.fill_rect(x, cy - 7, x + 24, cy + 7, landscape_scale_color(0.1));
        c.marker({x + 12.0, cy}, 2.8, MarkerShape::Circle, kDot, kWhite);
        break;
      case LegendItem::Pinned:
        c.marker({x + 12.0, cy}, 3.4, MarkerShape::Diamond, kPinned, kDot);
        break;
      case LegendItem::Contour:
        c.line({x, cy}, {x + 24.0, cy}, 0.9, kInk, 0.6);
        break;
      case LegendItem::Wall:
        c.line({x, cy}, {x + 24.0, cy}, 3.0, kInk);
        break;
      case LegendItem::Dashed:
        c.polyline({{x, cy}, {x + 24.0, cy}}, 1.4, kInk, 0.85, 6.0);
        break;
      case LegendItem::Rest:
        c.ring({x + 12.0, cy}, 4.5, 1.6, kInk);
        break;
    }
    c.text(item.text, sx, y, 12.0, kInk);
    y += kLegendLine;
  }
}

}  // namespace

LandscapeDomain chart_domain(const LandscapeChartSpec& spec) {
  return spec.models.size() == 1 ? landscape_domain(spec.models[0]) : common_landscape_domain();
}

std::unique_ptr<Canvas> landscape_chart(const LandscapeChartSpec& spec, ChartFormat format) {
  const Layout l = layout(spec);
  auto canvas = std::make_unique<Canvas>(l.width, l.height, format);
  Canvas& c = *canvas;
  double y = 12.0;
  for (const std::string& line : l.title_lines) {
    y += kTitleSize * 1.3;
    c.text(line, 16.0, y - 4.0, kTitleSize, kInk);
  }
  for (const std::string& line : l.caption_lines) {
    y += kCaptionSize * 1.5;
    c.text(line, 16.0, y - 4.0, kCaptionSize, kMuted);
  }
  const LandscapeScale scale = landscape_scale(spec.lame);
  const std::vector<double> levels = landscape_contour_levels(scale);
  for (size_t i = 0; i < spec.models.size(); ++i)
    panel(c, l, i, spec.models[i], spec, scale, levels, format != ChartFormat::Png);
  const bool forbidden_shown = any_barrier_model(spec) && l.domain.s2_min < 0.0;
  color_bar(c, l, scale, levels, forbidden_shown);
  legend(c, l, spec);
  double ny = l.notes_top;
  for (const auto& paragraph : l.notes) {
    for (const std::string& line : paragraph) {
      ny += kNoteSize * 1.35;
      c.text(line, kLeft, ny, kNoteSize, kMuted);
    }
    ny += 6.0;
  }
  return canvas;
}

}  // namespace invfree
