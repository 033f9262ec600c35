// The live panel's parameter ranges and the rules that keep every edit valid: a value
// outside its range is clamped to the nearest valid value and a one-line note says so
// (the panel shows it); a non-finite value is not applied at all. The material can be
// edited as (mu, lambda) or as (E, nu) with the scene files' conversion
// (core/material.h); each edit keeps both pairs inside their ranges.
// Inputs: the current value(s) and the requested one. Outputs: the value to apply and
// the note ("" when the request was applied as asked).
#pragma once

#include <string>
#include <string_view>

#include "material/material.h"
#include "scene/scene_fields.h"

namespace invfree::live {

struct Range {
  double lo, hi;
};

// The sliders' ranges of scene keys: the "slider range" of each key's row in the scene field
// table (core/scene/scene_fields.cpp says why each is narrower than the key's valid range).
// {0, 0} for a key without one.
Range slider_range(std::string_view key);

inline const Range kMuRange = slider_range("material.mu");          // Pa
inline const Range kLambdaRange = slider_range("material.lambda");  // Pa
constexpr double kLambdaLogMin = 1e2;  // lambda's slider: 0 at its left end, then log from here
inline const Range kPoissonRange = slider_range("material.nu");
inline const Range kTimeStepRange = slider_range("time.h");  // s
inline const Range kTolRange = slider_range("time.tol");     // Newton tolerance on |p|_inf / h, m/s
inline const Range kFrictionRange = slider_range("ground.friction");
// The panel's "ceiling speed" is the downward speed, -ceiling.velocity (m/s).
// (0.0 - x: a velocity of 0 is a speed of +0, not -0.)
inline const Range kCeilingSpeedRange = {0.0 - slider_range("ceiling.velocity").hi,
                                         0.0 - slider_range("ceiling.velocity").lo};
inline const Range kSpringStiffnessRange = slider_range("mass_spring.stiffness");  // N/m
// n_seg's slider starts at the key's smallest value; its end is measured (PanelState).
inline const int kMinSegments = static_cast<int>(find_value_bounds("mesh.n_seg")->lo);
// Not a scene key: the stiffness of the spring the mouse pulls with (N/m).
constexpr Range kPullStiffnessRange{1e1, 1e7};

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
