// The energy landscape of a model over its singular values (issue 26, the lecture's "Psi in
// the diagonal space"): Psi_hat(s1, s2) = Psi(diag(s1, s2)) on a grid, its contour lines
// (marching squares at log-spaced levels), the colour of a value, and every triangle's
// current (s1, s2). Plain numbers without Cairo or GL: the chart (`invfree landscape`,
// app/landscape/landscape_chart.h), the live panel and the web page draw the same thing.
//
// For a rotation-invariant model (neo-Hookean, ARAP, stable neo-Hookean) Psi(F) =
// Psi_hat(sigma(F)), so a triangle's dot sits on its own energy. Linear elasticity is not
// rotation invariant: its Psi_hat is Psi at U = V = I, and a rotated triangle's energy
// differs from the value under its dot (the chart says so).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "app/colormap.h"
#include "material/material.h"
#include "simulation.h"

namespace invfree {

// A point of the diagonal space: the polar SVD's signed singular values (s1 >= |s2|, s2 < 0
// exactly when the triangle is inverted).
struct SigmaPair {
  double s1 = 1.0, s2 = 1.0;
};

// The rectangle of the (s1, s2) plane drawn. s1 runs over [0, 2] (s1 = 0 is a column of the
// grid: neo-Hookean's +infinity there is a true value, not a sampling accident).
struct LandscapeDomain {
  double s1_min = 0.0, s1_max = 2.0;
  double s2_min = -2.0, s2_max = 2.0;
  bool operator==(const LandscapeDomain&) const = default;
};

// The domain a model is drawn on alone. The invertible models (linear, ARAP, stable
// neo-Hookean) are finite for s2 < 0 and their triangles do go there, so they get the whole
// inverted quadrant, s2 in [-2, 2]. Neo-Hookean is +infinity for every s1 s2 <= 0 and its
// triangles never leave s2 > 0 (the line search's filter), so the inverted quadrant would be
// one flat "forbidden" block: it gets a strip of it, s2 in [-0.5, 2], enough to show the
// wall from both sides.
LandscapeDomain landscape_domain(Model model);
// The domain shared by the four models side by side (`--model all`): the invertible models',
// so the panels compare point for point.
LandscapeDomain common_landscape_domain();

// Psi_hat(s1, s2) = Psi(diag(s1, s2)) in Pa (+infinity for neo-Hookean where s1 s2 <= 0).
double landscape_psi(Model model, const Lame& lame, double s1, double s2);

// Psi_hat at the nodes of a regular n1 x n2 lattice over the domain (corners included).
struct LandscapeGrid {
  Model model = Model::NeoHookean;
  Lame lame;
  LandscapeDomain domain;
  int n1 = 0, n2 = 0;       // nodes along s1 and s2 (>= 2 each)
  std::vector<double> psi;  // node (i, j) at i + n1 * j; j = 0 is s2_min
  double s1(int i) const { return domain.s1_min + (domain.s1_max - domain.s1_min) * i / (n1 - 1); }
  double s2(int j) const { return domain.s2_min + (domain.s2_max - domain.s2_min) * j / (n2 - 1); }
  double at(int i, int j) const { return psi[static_cast<size_t>(i + n1 * j)]; }
};

// Fills *grid (reusing its storage). n1, n2 are clamped to >= 2. One visit_model for the
// whole grid: no per-node dispatch.
void build_landscape_grid(Model model, const Lame& lame, const LandscapeDomain& domain, int n1,
                          int n2, LandscapeGrid* grid);
// The lattice spacing the chart and the panel use: `per_unit` nodes per unit of sigma
// (both axes), so the cells are square.
void build_landscape_grid(Model model, const Lame& lame, const LandscapeDomain& domain,
                          int per_unit, LandscapeGrid* grid);

// The colour scale: logarithmic in Psi from `lo` to `hi` (Pa). Neo-Hookean goes to +infinity
// as s1 s2 -> 0 and every model is 0 at rest, so a linear scale would show one colour
// everywhere but at the wall; decades read. Values <= lo take the first colour, >= hi the
// last; +infinity (and NaN) is the forbidden colour, which is on no scale.
struct LandscapeScale {
  double lo = 10.0, hi = 1e4;
  bool operator==(const LandscapeScale&) const = default;
};
// From the Lame parameters alone, so every model drawn with them shares it: hi is
// 4 (mu + lambda) rounded up to 1, 2 or 5 x 10^k -- twice linear elasticity's value at a
// uniform stretch by 2 (s1 = s2 = 2), which keeps the invertible models below saturation on
// nearly all of the domain -- and lo = hi / 1000: three decades, so that the bowl around
// rest (a few per cent of strain costs ~lo) is pale and the landscape beyond reads in steps.
LandscapeScale landscape_scale(const Lame& lame);
// Position of `psi` on the scale in [0, 1] (NaN for +infinity and NaN: forbidden).
double landscape_scale_position(const LandscapeScale& scale, double psi);
// Contour levels: 1 and 3 x 10^k Pa inside [lo, hi] (two a decade: log-spaced, round numbers).
std::vector<double> landscape_contour_levels(const LandscapeScale& scale);

// The sequential map (ColorBrewer YlOrRd: pale at rest, dark red at hi), and the forbidden
// colour: a cool grey that is on no warm scale and is not the renders' inverted green (for
// the invertible models the inverted quadrant has finite energy and is coloured by it).
inline constexpr Rgb kForbiddenColor{0.50f, 0.52f, 0.58f};
Rgb landscape_scale_color(double t);  // t in [0, 1]
Rgb landscape_color(const LandscapeScale& scale, double psi);

// A stress or energy density for people, three significant digits with its unit:
// "300 Pa", "35.7 kPa", "1 MPa", "+∞" (also the contour labels and the colour bar's ticks).
std::string format_pascal(double value);

// One contour line: a chain of points (s1, s2) where Psi_hat = level. Marching squares on the
// grid with linear interpolation along cell edges; cells with a non-finite corner are skipped
// (the line stops one cell short of neo-Hookean's wall); the saddle cases are resolved by the
// mean of the four corners.
struct ContourLine {
  double level = 0.0;
  bool closed = false;  // a loop: its last point repeats its first
  std::vector<SigmaPair> points;
};
// Appends the lines of every level to *out (cleared first).
void landscape_contours(const LandscapeGrid& grid, std::span<const double> levels,
                        std::vector<ContourLine>* out);

// Where Psi_hat is +infinity for the model: neo-Hookean's s1 s2 <= 0 (the wall is s2 = 0 for
// s1 > 0, and the column s1 = 0); false everywhere for the invertible models.
bool landscape_forbidden(Model model, double s1, double s2);

// Every triangle's (s1, s2), from polar_svd of its deformation gradient, into *out (resized;
// no allocation once it has the size).
void triangle_sigmas(const Simulation& sim, std::vector<SigmaPair>* out);

// What a live redraw keeps between frames: the grid, its scale and its contours, rebuilt only
// when the model, the Lame parameters, the domain or the resolution change.
struct LandscapeCache {
  bool valid = false;
  int per_unit = 0;
  LandscapeGrid grid;
  LandscapeScale scale;
  std::vector<double> levels;
  std::vector<ContourLine> contours;
  int rebuilds = 0;  // how many times the grid was built (tests, benchmarks)
};
// Brings *cache up to date; returns true when it had to rebuild.
bool update_landscape_cache(Model model, const Lame& lame, const LandscapeDomain& domain,
                            int per_unit, LandscapeCache* cache);

}  // namespace invfree
