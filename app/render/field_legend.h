// The words and numbers of a triangle field's legend (Psi, stress, clamped; det F's are
// frame_text.h's), as plain strings without GL so that they can be tested directly: the
// field's summary over a frame, the automatic scale chosen from it, the bar's ticks with
// round labels, and the bar's title and notes. The colours are app/field_colormap.h's.
#pragma once

#include <string>
#include <vector>

#include "app/field_colormap.h"
#include "triangle_fields.h"

namespace invfree::render {

// A field's values over a frame's triangles (non-finite ones left out).
struct FieldStats {
  double min = 0.0, max = 0.0;
  double min_positive = 0.0;  // the smallest value > 0 (0: none)
  double max_abs = 0.0;
  int count = 0;                                 // finite values
  int category_counts[kClampedCategories] = {};  // clamped: triangles per count 0..4
};
FieldStats field_stats(TriangleField field, const std::vector<double>& values);
// The stats of a and b's values together (frames shown side by side, a movie's frames so
// far): the extremes of both, the counts added. A side with no values adds nothing.
FieldStats combine_field_stats(const FieldStats& a, const FieldStats& b);

// The automatic scale of the field over a frame with these stats (det F: auto_det_f_range).
FieldScale auto_field_scale(TriangleField field, const FieldStats& stats);

// "10 kPa", "2.5 MPa", "−20 kPa", "500 Pa", "0": up to three significant digits, no
// trailing zeros, an SI prefix chosen by the value itself; a minus sign, not a hyphen.
std::string format_round_si(double value, const char* unit);

// The unit a stress bar is labelled in: Pa with the SI prefix of the scale's top (so every
// label of the bar has the same, said once in the subtitle), e.g. {1e3, "kPa"}. Psi's
// labels span decades, each with its own prefix (format_round_si): Pa here.
struct FieldUnit {
  double factor = 1.0;
  std::string name = "Pa";
};
FieldUnit field_unit(const FieldScale& scale);
// `value` in `unit` without the unit's name: up to three significant digits, no trailing
// zeros, a minus sign ("−89.3", "250", "0.02", "0").
std::string format_in_unit(double value, const FieldUnit& unit);

// A tick of a field's bar: its value, its height on the bar (0 bottom, 1 top) and label.
struct FieldTick {
  double value = 0.0;
  double position = 0.0;
  std::string label;
};
// Psi: the scale's ends (the bottom "≤ lo": less energy takes its colour) and every decade
// between them (under two decades 2 and 5 times them too) not crowding another tick,
// each as format_round_si; stress: -S, -S/2, 0, S/2, S in field_unit's unit; clamped:
// each category at its box's middle ("0" .. "4").
std::vector<FieldTick> field_bar_ticks(const FieldScale& scale);

// The bar's heading: the field's name with "(auto scale)" when the scale came from the
// data, a line saying what it is and its unit (field_unit's; wrapped by the caller), and
// the notes at the bar's top and bottom ends ("" for none).
struct FieldLegendWords {
  std::string title;
  std::string subtitle;
  std::string top_note, bottom_note;
};
FieldLegendWords field_legend_words(const FieldScale& scale);

// Splits `text` at spaces into lines no wider than `max_width` by `width_of` (a word wider
// than that gets a line of its own); a '\n' always starts a new line.
template <class WidthOf>
std::vector<std::string> wrap_words(const std::string& text, double max_width, WidthOf width_of) {
  std::vector<std::string> lines;
  size_t para_start = 0;
  while (para_start <= text.size()) {
    size_t para_end = text.find('\n', para_start);
    if (para_end == std::string::npos) para_end = text.size();
    std::string line;
    size_t start = para_start;
    while (start <= para_end) {
      size_t end = text.find(' ', start);
      if (end == std::string::npos || end > para_end) end = para_end;
      const std::string word = text.substr(start, end - start);
      if (!word.empty()) {
        const std::string longer = line.empty() ? word : line + " " + word;
        if (!line.empty() && width_of(longer) > max_width) {
          lines.push_back(line);
          line = word;
        } else {
          line = longer;
        }
      }
      start = end + 1;
    }
    if (!line.empty()) lines.push_back(line);
    para_start = para_end + 1;
  }
  return lines;
}

}  // namespace invfree::render
