// The colours of every stability picture (the contact sheet, its pages and the summary
// slide), defined once so a class reads them alike on each: a failure is red, an inversion
// its model allows a neutral slate blue (neither ok's ink nor a failure's red), n/a grey,
// and an ok run is drawn in ink or filled with the det F colour of its smallest det F.
// `class_ink` is the strong colour (a thumbnail's frame, a caption, the key's text);
// `class_fill` fills a table cell, the same hue made light where dark text must read on it.
#pragma once

#include <cmath>

#include "app/colormap.h"
#include "app/study/stability.h"

namespace invfree {

constexpr Rgb kSheetInk{0.10f, 0.10f, 0.12f};
constexpr Rgb kSheetMuted{0.42f, 0.42f, 0.45f};
constexpr Rgb kSheetWhite{1.0f, 1.0f, 1.0f};
constexpr Rgb kSheetFailed{0.80f, 0.10f, 0.12f};
constexpr Rgb kSheetAllowed{0.25f, 0.36f, 0.62f};
constexpr Rgb kSheetAllowedFill{0.80f, 0.85f, 0.95f};
constexpr Rgb kSheetNotApplicableFill{0.93f, 0.93f, 0.93f};

inline Rgb class_ink(CellClass c) {
  switch (c) {
    case CellClass::Failed:
      return kSheetFailed;
    case CellClass::InversionAllowed:
      return kSheetAllowed;
    case CellClass::NotApplicable:
      return kSheetMuted;
    case CellClass::Ok:
      break;
  }
  return kSheetInk;
}

// An ok cell is filled with the colour of its smallest det F (white if unknown).
inline Rgb class_fill(CellClass c, double min_det_f) {
  switch (c) {
    case CellClass::Failed:
      return kSheetFailed;
    case CellClass::InversionAllowed:
      return kSheetAllowedFill;
    case CellClass::NotApplicable:
      return kSheetNotApplicableFill;
    case CellClass::Ok:
      break;
  }
  return std::isfinite(min_det_f) ? det_f_color(min_det_f) : kSheetWhite;
}

// Black or white text, whichever reads on `fill`.
inline Rgb ink_on(Rgb fill) {
  return 0.30 * fill.r + 0.59 * fill.g + 0.11 * fill.b > 0.55 ? kSheetInk : kSheetWhite;
}

}  // namespace invfree
