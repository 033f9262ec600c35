#include "app/live/param_limits.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace invfree::live {

Range slider_range(std::string_view key) {
  const SceneField* f = find_scene_field(key);
  return f ? Range{f->slider.lo, f->slider.hi} : Range{0.0, 0.0};
}

std::string format_value(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

namespace {

// (snprintf rather than chains of std::string +: GCC 12 -O3 warns falsely on those, PR105329)
std::string range_text(Range r, const char* unit) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.4g, %.4g]%s%s", r.lo, r.hi, *unit ? " " : "", unit);
  return buf;
}

// c(nu) = lambda / E = nu / ((1 + nu)(1 - 2 nu)), increasing on [0, 0.5).
double lambda_per_young(double nu) {
  return nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

// The largest nu in [0, 0.5) with lambda_per_young(nu) <= c (bisection; c >= 0).
double poisson_for_lambda_per_young(double c) {
  double a = 0.0, b = 0.5;
  for (int i = 0; i < 200 && b - a > 1e-15; ++i) {
    const double m = 0.5 * (a + b);
    (lambda_per_young(m) <= c ? a : b) = m;
  }
  return a;
}

MaterialEdit from_young_poisson(double E, double nu, std::string note) {
  MaterialEdit e{lame_from_young_poisson(E, nu), std::move(note)};
  // Round-off at the ends of the ranges must not leave them.
  e.lame.mu = std::clamp(e.lame.mu, kMuRange.lo, kMuRange.hi);
  e.lame.lambda = std::clamp(e.lame.lambda, kLambdaRange.lo, kLambdaRange.hi);
  return e;
}

}  // namespace

Clamped clamp_to_range(double requested, double current, Range range, const char* name,
                       const char* unit) {
  char buf[192];
  if (!std::isfinite(requested)) {
    std::snprintf(buf, sizeof buf, "%s: not a finite number, not applied (kept %.4g)", name,
                  current);
    return {current, buf};
  }
  const double v = std::clamp(requested, range.lo, range.hi);
  if (v == requested) return {v, ""};
  std::snprintf(buf, sizeof buf, "%s = %.4g is outside %s; clamped to %.4g", name, requested,
                range_text(range, unit).c_str(), v);
  return {v, buf};
}

MaterialEdit edit_mu(const Lame& current, double mu) {
  const Clamped c = clamp_to_range(mu, current.mu, kMuRange, "mu", "Pa");
  return {{c.value, current.lambda}, c.note};
}

MaterialEdit edit_lambda(const Lame& current, double lambda) {
  const Clamped c = clamp_to_range(lambda, current.lambda, kLambdaRange, "lambda", "Pa");
  return {{current.mu, c.value}, c.note};
}

MaterialEdit edit_young(const Lame& current, double youngs) {
  double E0, nu;
  young_poisson_from_lame(current, &E0, &nu);
  // mu = E / (2(1 + nu)) and lambda = E c(nu) must stay in range at this nu.
  Range r{2.0 * (1.0 + nu) * kMuRange.lo, 2.0 * (1.0 + nu) * kMuRange.hi};
  const double c = lambda_per_young(nu);
  if (c > 0.0) r.hi = std::min(r.hi, kLambdaRange.hi / c);
  const Clamped e = clamp_to_range(youngs, E0, r, "E", "Pa");
  if (!std::isfinite(youngs)) return {current, e.note};
  std::string note = e.note;
  if (!note.empty()) note += " (the range of E at nu = " + format_value(nu) + ")";
  return from_young_poisson(e.value, nu, note);
}

MaterialEdit edit_poisson(const Lame& current, double poisson) {
  double E, nu0;
  young_poisson_from_lame(current, &E, &nu0);
  Range r = kPoissonRange;
  // lambda = E c(nu) <= lambda_max, and mu = E / (2(1 + nu)) >= mu_min.
  r.hi = std::min(r.hi, poisson_for_lambda_per_young(kLambdaRange.hi / E));
  r.hi = std::min(r.hi, E / (2.0 * kMuRange.lo) - 1.0);
  r.hi = std::max(r.hi, r.lo);
  const Clamped p = clamp_to_range(poisson, nu0, r, "nu", "");
  if (!std::isfinite(poisson)) return {current, p.note};
  std::string note = p.note;
  if (!note.empty() && r.hi < kPoissonRange.hi)
    note += " (the range of nu at E = " + format_value(E) + ")";
  return from_young_poisson(E, p.value, note);
}

Range ceiling_stop_range(double ground_y, bool has_ground, double ceiling_start, double side) {
  const double lo = has_ground ? ground_y + 0.1 * side : ceiling_start - 2.0 * side;
  return {std::min(lo, ceiling_start), ceiling_start};
}

}  // namespace invfree::live
