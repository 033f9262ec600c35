// The live panel's parameter ranges and the rules that keep every edit valid: a value
// outside its range is clamped to the nearest valid value and a one-line note says so
// (the panel shows it); a non-finite value is not applied at all. The material can be
// edited as (mu, lambda) or as (E, nu) with the scene files' conversion
// (core/material.h); each edit keeps both pairs inside their ranges.
// Inputs: the current value(s) and the requested one. Outputs: the value to apply and
// the note ("" when the request was applied as asked).
#pragma once

#include <string>

#include "material/material.h"

namespace invfree::live {

struct Range {
  double lo, hi;
};

// Lame parameters (Pa). mu > 0 is required by every model; lambda >= 0 (nu >= 0). The
// upper ends are where the `compress` demo's penalty ceiling still makes progress (much
// stiffer squares hit Newton's iteration cap under it: the run pauses with a banner).
constexpr Range kMuRange{1e2, 1e7};
constexpr Range kLambdaRange{0.0, 1e8};
constexpr double kLambdaLogMin = 1e2;  // lambda's slider: 0 at its left end, then log from here
constexpr Range kPoissonRange{0.0, 0.499};
constexpr Range kTimeStepRange{1e-4, 0.05};  // h, s
constexpr Range kTolRange{1e-5, 1.0};        // Newton tolerance on |p|_inf / h, m/s
constexpr Range kFrictionRange{0.0, 2.0};
constexpr Range kCeilingSpeedRange{0.0, 5.0};   // m/s, downwards
constexpr Range kPullStiffnessRange{1e1, 1e7};  // N/m of the grab spring
constexpr int kMinSegments = 1;

struct Clamped {
  double value;
  std::string note;  // "" when `requested` was applied unchanged
};

// Clamps `requested` into `range`. Non-finite: keeps `current`, with a note.
// `name` and `unit` only make the note readable ("h = 1 s is out of range ...").
Clamped clamp_to_range(double requested, double current, Range range, const char* name,
                       const char* unit);

struct MaterialEdit {
  Lame lame;
  std::string note;
};

MaterialEdit edit_mu(const Lame& current, double mu);
MaterialEdit edit_lambda(const Lame& current, double lambda);
MaterialEdit edit_young(const Lame& current, double youngs);     // keeps nu
MaterialEdit edit_poisson(const Lame& current, double poisson);  // keeps E

// Range of the ceiling's stop height for a scene: from a tenth of the side above the
// ground (squashing further only produces a Newton failure) to the ceiling's start.
Range ceiling_stop_range(double ground_y, bool has_ground, double ceiling_start, double side);

// Formats a value compactly for notes and slider labels ("3.571e+04" -> "35714", "1e+08").
std::string format_value(double v);

}  // namespace invfree::live
