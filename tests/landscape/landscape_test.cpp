// The landscape's numbers (app/landscape/landscape.h): the grid is the models' own energy
// density, neo-Hookean is +infinity exactly where s1 s2 <= 0 and the invertible models are
// finite there, the contours lie on their levels and close around the rest point, the
// triangles' points are their polar SVDs, and the cache rebuilds only when its inputs change.
#include "app/landscape/landscape.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "material/models.h"
#include "material/polar_svd.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "triangle_fields.h"

namespace invfree {
namespace {

const Lame kLame = lame_from_young_poisson(1e5, 0.4);
constexpr Model kAll[] = {Model::NeoHookean, Model::Linear, Model::Arap, Model::StableNeoHookean};

Mat2 diag(double a, double b) {
  Mat2 F;
  F << a, 0.0, 0.0, b;
  return F;
}

TEST(Landscape, GridIsTheModelsEnergyDensityAtDiagSigma) {
  for (Model m : kAll) {
    LandscapeGrid g;
    build_landscape_grid(m, kLame, common_landscape_domain(), 10, &g);
    ASSERT_EQ(g.n1, 21);
    ASSERT_EQ(g.n2, 41);
    EXPECT_DOUBLE_EQ(g.s1(0), 0.0);
    EXPECT_DOUBLE_EQ(g.s1(g.n1 - 1), 2.0);
    EXPECT_DOUBLE_EQ(g.s2(0), -2.0);
    EXPECT_DOUBLE_EQ(g.s2(g.n2 - 1), 2.0);
    for (int j = 0; j < g.n2; ++j)
      for (int i = 0; i < g.n1; ++i) {
        const double expected = energy_density(m, diag(g.s1(i), g.s2(j)), kLame);
        if (std::isinf(expected))
          EXPECT_TRUE(std::isinf(g.at(i, j)));
        else
          EXPECT_EQ(g.at(i, j), expected) << model_name(m) << " at " << g.s1(i) << ", " << g.s2(j);
        EXPECT_EQ(landscape_psi(m, kLame, g.s1(i), g.s2(j)), g.at(i, j));
      }
  }
}

TEST(Landscape, NeoHookeanIsForbiddenExactlyWhereTheProductIsNotPositive) {
  LandscapeGrid g;
  build_landscape_grid(Model::NeoHookean, kLame, common_landscape_domain(), 20, &g);
  const LandscapeScale scale = landscape_scale(kLame);
  int forbidden = 0;
  for (int j = 0; j < g.n2; ++j)
    for (int i = 0; i < g.n1; ++i) {
      const double s1 = g.s1(i), s2 = g.s2(j), psi = g.at(i, j);
      const bool wall = !(s1 * s2 > 0.0);
      EXPECT_EQ(std::isinf(psi) && psi > 0, wall) << s1 << ", " << s2;
      EXPECT_EQ(std::isfinite(psi), !wall) << s1 << ", " << s2;
      EXPECT_EQ(landscape_forbidden(Model::NeoHookean, s1, s2), wall);
      const Rgb c = landscape_color(scale, psi);
      const bool grey =
          c.r == kForbiddenColor.r && c.g == kForbiddenColor.g && c.b == kForbiddenColor.b;
      EXPECT_EQ(grey, wall) << s1 << ", " << s2;
      forbidden += wall;
    }
  // The whole s1 = 0 column, and the rows s2 <= 0 (half the rows and the one at 0) of the others.
  EXPECT_EQ(forbidden, g.n2 + (g.n1 - 1) * (g.n2 / 2 + 1));
  // Its own domain keeps a strip of the inverted quadrant: the wall is seen from both sides.
  const LandscapeDomain d = landscape_domain(Model::NeoHookean);
  EXPECT_LT(d.s2_min, 0.0);
  EXPECT_GT(d.s2_min, -2.0);
}

TEST(Landscape, InvertibleModelsAreFiniteThroughZeroAndIntoInversion) {
  for (Model m : {Model::Linear, Model::Arap, Model::StableNeoHookean}) {
    const LandscapeDomain d = landscape_domain(m);
    EXPECT_EQ(d, common_landscape_domain()) << model_name(m);
    LandscapeGrid g;
    build_landscape_grid(m, kLame, d, 20, &g);
    const LandscapeScale scale = landscape_scale(kLame);
    for (int j = 0; j < g.n2; ++j)
      for (int i = 0; i < g.n1; ++i) {
        EXPECT_TRUE(std::isfinite(g.at(i, j)))
            << model_name(m) << " " << g.s1(i) << ", " << g.s2(j);
        EXPECT_FALSE(landscape_forbidden(m, g.s1(i), g.s2(j)));
        EXPECT_FALSE(std::isnan(landscape_scale_position(scale, g.at(i, j))));
      }
  }
}

TEST(Landscape, EveryModelIsZeroAtRest) {
  for (Model m : kAll) EXPECT_NEAR(landscape_psi(m, kLame, 1.0, 1.0), 0.0, 1e-9) << model_name(m);
}

TEST(Landscape, ScaleAndLevelsAreLogSpacedRoundNumbers) {
  const LandscapeScale s = landscape_scale(kLame);  // 4 (mu + lambda) = 714 kPa -> 1 MPa
  EXPECT_DOUBLE_EQ(s.hi, 1e6);
  EXPECT_DOUBLE_EQ(s.lo, 1000.0);
  const auto levels = landscape_contour_levels(s);
  const std::vector<double> expected = {1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6};
  ASSERT_EQ(levels.size(), expected.size());
  for (size_t k = 0; k < levels.size(); ++k)
    EXPECT_NEAR(levels[k], expected[k], 1e-9 * expected[k]);
  EXPECT_EQ(landscape_scale_position(s, 0.0), 0.0);
  EXPECT_EQ(landscape_scale_position(s, 500.0), 0.0);
  EXPECT_NEAR(landscape_scale_position(s, 1e4), 1.0 / 3.0, 1e-12);
  EXPECT_EQ(landscape_scale_position(s, 1e9), 1.0);
  EXPECT_TRUE(std::isnan(landscape_scale_position(s, INFINITY)));
  EXPECT_TRUE(std::isnan(landscape_scale_position(s, NAN)));
  // Rounded up to 1, 2 or 5 x 10^k.
  EXPECT_DOUBLE_EQ(landscape_scale({1000.0, 0.0}).hi, 5000.0);    // 4000
  EXPECT_DOUBLE_EQ(landscape_scale({1000.0, 250.0}).hi, 5000.0);  // 5000 exactly
  EXPECT_DOUBLE_EQ(landscape_scale({1000.0, 300.0}).hi, 1e4);     // 5200
}

TEST(Landscape, ColoursRunFromPaleToDarkAndTheForbiddenOneIsOnNoScale) {
  const Rgb pale = landscape_scale_color(0.0), dark = landscape_scale_color(1.0);
  EXPECT_GT(pale.r + pale.g + pale.b, 2.5f);
  EXPECT_LT(dark.r + dark.g + dark.b, 0.8f);
  float last = 4.0f;
  for (int k = 0; k <= 100; ++k) {
    const Rgb c = landscape_scale_color(k / 100.0);
    const float lum = 0.3f * c.r + 0.59f * c.g + 0.11f * c.b;
    EXPECT_LE(lum, last + 1e-6f) << k;  // monotone: darker means more energy
    last = lum;
    // The forbidden grey is bluish: on the warm scale no colour has b > r.
    EXPECT_GE(c.r, c.b);
  }
  EXPECT_GT(kForbiddenColor.b, kForbiddenColor.r);
}

TEST(Landscape, FormatsPascals) {
  EXPECT_EQ(format_pascal(300.0), "300 Pa");
  EXPECT_EQ(format_pascal(35714.2857), "35.7 kPa");
  EXPECT_EQ(format_pascal(1e6), "1 MPa");
  EXPECT_EQ(format_pascal(INFINITY), "+\u221e");
}

// Every contour point lies on a grid edge whose two end values bracket the level, at the
// linear interpolation between them; Psi there is the level to within what linear
// interpolation allows on that edge (|Psi(x) - level| <= h^2/8 max|Psi''| along it, bounded
// here by the second differences beside the edge, times 2 for the variation between them);
// and the largest relative error falls as h^2 when the grid is refined (second order).
// Returns that largest relative error.
double check_contours(Model m, int per_unit) {
  LandscapeGrid g;
  build_landscape_grid(m, kLame, landscape_domain(m), per_unit, &g);
  const auto levels = landscape_contour_levels(landscape_scale(kLame));
  std::vector<ContourLine> lines;
  landscape_contours(g, levels, &lines);
  EXPECT_FALSE(lines.empty());
  const double h1 = g.s1(1) - g.s1(0), h2 = g.s2(1) - g.s2(0);
  long checked = 0;
  double worst = 0.0;
  for (const ContourLine& line : lines) {
    EXPECT_GE(line.points.size(), 2u);
    for (const SigmaPair& p : line.points) {
      const double fi = (p.s1 - g.domain.s1_min) / h1, fj = (p.s2 - g.domain.s2_min) / h2;
      const bool on_vertical = std::abs(fi - std::round(fi)) < 1e-9;
      const bool on_horizontal = std::abs(fj - std::round(fj)) < 1e-9;
      EXPECT_TRUE(on_vertical || on_horizontal) << p.s1 << ", " << p.s2;
      const double psi = landscape_psi(m, kLame, p.s1, p.s2);
      worst = std::max(worst, std::abs(psi - line.level) / line.level);
      ++checked;
      if (on_vertical && on_horizontal) {  // on a node (t within 1e-9 of 0 or 1)
        const double node =
            g.at(static_cast<int>(std::round(fi)), static_cast<int>(std::round(fj)));
        EXPECT_NEAR(node, line.level, 1e-6 * line.level);
        continue;
      }
      // The edge's two nodes and the second differences beside them.
      int i0, j0, di, dj;
      if (on_horizontal) {
        j0 = static_cast<int>(std::round(fj));
        i0 = std::min(static_cast<int>(std::floor(fi)), g.n1 - 2);
        di = 1, dj = 0;
      } else {
        i0 = static_cast<int>(std::round(fi));
        j0 = std::min(static_cast<int>(std::floor(fj)), g.n2 - 2);
        di = 0, dj = 1;
      }
      const double a = g.at(i0, j0), b = g.at(i0 + di, j0 + dj);
      EXPECT_LE(std::min(a, b), line.level);
      EXPECT_GE(std::max(a, b), line.level);
      const double t = on_horizontal ? fi - i0 : fj - j0;
      EXPECT_NEAR(a + t * (b - a), line.level, 1e-9 * line.level);
      double second = 0.0;
      for (int k = -1; k <= 1; k += 2) {
        const int ia = i0 + (k < 0 ? -di : 2 * di), ja = j0 + (k < 0 ? -dj : 2 * dj);
        if (ia < 0 || ja < 0 || ia >= g.n1 || ja >= g.n2) continue;
        const double near = k < 0 ? a : b, far = k < 0 ? b : a;
        const double d2 = g.at(ia, ja) - 2.0 * near + far;
        if (std::isfinite(d2)) second = std::max(second, std::abs(d2));
      }
      const double bound = 2.0 * second / 8.0 + 1e-9 * line.level;
      EXPECT_LE(std::abs(psi - line.level), bound)
          << model_name(m) << " level " << line.level << " at " << p.s1 << ", " << p.s2;
    }
  }
  EXPECT_GT(checked, 500) << model_name(m);
  return worst;
}

TEST(Landscape, ContoursLieOnTheirLevels) {
  for (Model m : kAll) {
    const double coarse = check_contours(m, 100), fine = check_contours(m, 200);
    EXPECT_LT(fine, coarse / 3.0) << model_name(m) << ": " << coarse << " -> " << fine;
    std::printf(
        "%s: largest relative error of a contour point %.3g (100 nodes a unit), %.3g (200)\n",
        model_name(m), coarse, fine);
  }
}

TEST(Landscape, TheLowestContourIsOneLoopAroundRest) {
  for (Model m : kAll) {
    LandscapeGrid g;
    build_landscape_grid(m, kLame, landscape_domain(m), 100, &g);
    const double level = landscape_scale(kLame).lo;
    std::vector<ContourLine> lines;
    landscape_contours(g, std::span<const double>(&level, 1), &lines);
    ASSERT_EQ(lines.size(), 1u) << model_name(m);
    const ContourLine& loop = lines[0];
    EXPECT_TRUE(loop.closed);
    EXPECT_EQ(loop.points.front().s1, loop.points.back().s1);
    EXPECT_EQ(loop.points.front().s2, loop.points.back().s2);
    // It winds once around (1, 1): the angles' steps add up to 2 pi.
    double turn = 0.0;
    for (size_t k = 1; k < loop.points.size(); ++k) {
      const double a0 = std::atan2(loop.points[k - 1].s2 - 1.0, loop.points[k - 1].s1 - 1.0);
      const double a1 = std::atan2(loop.points[k].s2 - 1.0, loop.points[k].s1 - 1.0);
      turn += std::remainder(a1 - a0, 2.0 * M_PI);
    }
    EXPECT_NEAR(std::abs(turn), 2.0 * M_PI, 1e-6) << model_name(m);
  }
}

TEST(Landscape, NeoHookeanContoursStopShortOfTheWall) {
  LandscapeGrid g;
  build_landscape_grid(Model::NeoHookean, kLame, landscape_domain(Model::NeoHookean), 50, &g);
  const auto levels = landscape_contour_levels(landscape_scale(kLame));
  std::vector<ContourLine> lines;
  landscape_contours(g, levels, &lines);
  for (const ContourLine& line : lines)
    for (const SigmaPair& p : line.points) {
      EXPECT_GT(p.s1 * p.s2, 0.0);
      EXPECT_TRUE(std::isfinite(landscape_psi(Model::NeoHookean, kLame, p.s1, p.s2)));
    }
}

SceneDef scene(const std::string& name, const std::vector<std::string>& overrides) {
  SceneDef s = *load_builtin_scene(name).scene;
  for (const auto& o : overrides) {
    const std::string e = apply_override(s, o);
    EXPECT_TRUE(e.empty()) << e;
  }
  return s;
}

TEST(Landscape, TrianglePointsArePolarSvdsOfTheirF) {
  // A soft linear square thrown at the ground: some triangles invert (s2 < 0).
  Simulation sim = make_simulation(scene("compress", {"material.model=linear", "material.E=1e4",
                                                      "mesh.n_seg=8", "initial.velocity=[0,-8]"}));
  while (sim.step_count < 23) ASSERT_EQ(step(sim).status, StepStatus::Ok);
  std::vector<SigmaPair> s;
  triangle_sigmas(sim, &s);
  ASSERT_EQ(static_cast<int>(s.size()), sim.mesh.triangle_count());
  int inverted = 0;
  for (int t = 0; t < sim.mesh.triangle_count(); ++t) {
    const Mat2 F = triangle_deformation_gradient(sim, t);
    const Vec2 sigma = polar_svd(F).sigma;
    EXPECT_EQ(s[t].s1, sigma(0));
    EXPECT_EQ(s[t].s2, sigma(1));
    EXPECT_GE(s[t].s1, std::abs(s[t].s2));
    EXPECT_EQ(s[t].s2 < 0.0, determinant(F) < 0.0);
    inverted += s[t].s2 < 0.0;
  }
  EXPECT_GT(inverted, 0);
}

TEST(Landscape, CacheRebuildsOnlyWhenItsInputsChange) {
  LandscapeCache c;
  const LandscapeDomain d = landscape_domain(Model::NeoHookean);
  EXPECT_TRUE(update_landscape_cache(Model::NeoHookean, kLame, d, 32, &c));
  EXPECT_FALSE(update_landscape_cache(Model::NeoHookean, kLame, d, 32, &c));
  EXPECT_EQ(c.rebuilds, 1);
  EXPECT_FALSE(c.contours.empty());
  Lame other = kLame;
  other.mu *= 2.0;
  EXPECT_TRUE(update_landscape_cache(Model::NeoHookean, other, d, 32, &c));
  EXPECT_TRUE(update_landscape_cache(Model::Arap, other, landscape_domain(Model::Arap), 32, &c));
  EXPECT_TRUE(update_landscape_cache(Model::Arap, other, landscape_domain(Model::Arap), 16, &c));
  EXPECT_FALSE(update_landscape_cache(Model::Arap, other, landscape_domain(Model::Arap), 16, &c));
  EXPECT_EQ(c.rebuilds, 4);
  EXPECT_EQ(c.grid.n1, 33);
}

}  // namespace
}  // namespace invfree
