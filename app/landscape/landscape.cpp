#include "app/landscape/landscape.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "material/models.h"
#include "material/polar_svd.h"
#include "triangle_fields.h"

namespace invfree {

LandscapeDomain landscape_domain(Model model) {
  LandscapeDomain d;
  if (!model_allows_inversion(model)) d.s2_min = -0.5;
  return d;
}

LandscapeDomain common_landscape_domain() {
  return LandscapeDomain{};
}

namespace {

Mat2 diagonal(double s1, double s2) {
  Mat2 F;
  F << s1, 0.0, 0.0, s2;
  return F;
}

// The smallest 1, 2 or 5 x 10^k >= v (v > 0).
double nice_ceil_125(double v) {
  const double decade = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= v * (1.0 - 1e-12)) return m * decade;
  return 10.0 * decade;
}

}  // namespace

double landscape_psi(Model model, const Lame& lame, double s1, double s2) {
  return energy_density(model, diagonal(s1, s2), lame);
}

bool landscape_forbidden(Model model, double s1, double s2) {
  return !model_allows_inversion(model) && !(s1 * s2 > 0.0);
}

void build_landscape_grid(Model model, const Lame& lame, const LandscapeDomain& domain, int n1,
                          int n2, LandscapeGrid* grid) {
  grid->model = model;
  grid->lame = lame;
  grid->domain = domain;
  grid->n1 = std::max(n1, 2);
  grid->n2 = std::max(n2, 2);
  grid->psi.resize(static_cast<size_t>(grid->n1) * static_cast<size_t>(grid->n2));
  visit_model(model, [&](auto m) {
    using M = decltype(m);
    for (int j = 0; j < grid->n2; ++j) {
      const double s2 = grid->s2(j);
      double* row = grid->psi.data() + static_cast<size_t>(grid->n1) * j;
      for (int i = 0; i < grid->n1; ++i)
        row[i] = M::energy_density(diagonal(grid->s1(i), s2), lame);
    }
  });
}

void build_landscape_grid(Model model, const Lame& lame, const LandscapeDomain& domain,
                          int per_unit, LandscapeGrid* grid) {
  const int n1 = static_cast<int>(std::lround((domain.s1_max - domain.s1_min) * per_unit)) + 1;
  const int n2 = static_cast<int>(std::lround((domain.s2_max - domain.s2_min) * per_unit)) + 1;
  build_landscape_grid(model, lame, domain, n1, n2, grid);
}

LandscapeScale landscape_scale(const Lame& lame) {
  const double top = 4.0 * (lame.mu + lame.lambda);
  LandscapeScale s;
  s.hi = top > 0.0 && std::isfinite(top) ? nice_ceil_125(top) : 1e4;
  s.lo = s.hi * 1e-3;
  return s;
}

double landscape_scale_position(const LandscapeScale& scale, double psi) {
  if (!std::isfinite(psi)) return std::numeric_limits<double>::quiet_NaN();
  if (!(psi > scale.lo)) return 0.0;
  return std::min(std::log(psi / scale.lo) / std::log(scale.hi / scale.lo), 1.0);
}

std::vector<double> landscape_contour_levels(const LandscapeScale& scale) {
  std::vector<double> levels;
  const double first = std::pow(10.0, std::floor(std::log10(scale.lo)));
  for (double decade = first; decade <= scale.hi * (1.0 + 1e-12); decade *= 10.0)
    for (double m : {1.0, 3.0}) {
      const double v = m * decade;
      if (v >= scale.lo * (1.0 - 1e-12) && v <= scale.hi * (1.0 + 1e-12)) levels.push_back(v);
    }
  return levels;
}

Rgb landscape_scale_color(double t) {
  // ColorBrewer YlOrRd, 9 classes.
  static constexpr Rgb stops[] = {
      {1.000f, 1.000f, 0.800f}, {1.000f, 0.929f, 0.627f}, {0.996f, 0.851f, 0.463f},
      {0.996f, 0.698f, 0.298f}, {0.992f, 0.553f, 0.235f}, {0.988f, 0.306f, 0.165f},
      {0.890f, 0.102f, 0.110f}, {0.741f, 0.000f, 0.149f}, {0.502f, 0.000f, 0.149f}};
  constexpr int last = static_cast<int>(std::size(stops)) - 1;
  const double u = std::clamp(t, 0.0, 1.0) * last;
  const int i = std::min(static_cast<int>(u), last - 1);
  const float f = static_cast<float>(u - i);
  const Rgb a = stops[i], b = stops[i + 1];
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}

std::string format_pascal(double value) {
  if (std::isinf(value)) return value > 0 ? "+\u221e" : "\u2212\u221e";
  const double a = std::abs(value);
  const char* unit = a >= 1e9 ? "GPa" : a >= 1e6 ? "MPa" : a >= 1e3 ? "kPa" : "Pa";
  const double scale = a >= 1e9 ? 1e9 : a >= 1e6 ? 1e6 : a >= 1e3 ? 1e3 : 1.0;
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3g %s", value / scale, unit);
  return buf;
}

Rgb landscape_color(const LandscapeScale& scale, double psi) {
  const double t = landscape_scale_position(scale, psi);
  return std::isnan(t) ? kForbiddenColor : landscape_scale_color(t);
}

namespace {

// One marching-squares segment: its two ends, each on a grid edge (named by id so that the
// segments of neighbouring cells can be chained).
struct Segment {
  std::array<long, 2> edge;
  std::array<SigmaPair, 2> point;
};

// Chains the segments of one level into lines (each grid edge is shared by at most two
// segments, one in each cell beside it).
void chain_segments(const std::vector<Segment>& segs, double level, std::vector<ContourLine>* out) {
  // (edge id, segment index * 2 + end), sorted: the two ends on one edge are neighbours.
  std::vector<std::pair<long, int>> ends;
  ends.reserve(segs.size() * 2);
  for (size_t s = 0; s < segs.size(); ++s)
    for (int e = 0; e < 2; ++e) ends.emplace_back(segs[s].edge[e], static_cast<int>(s * 2 + e));
  std::sort(ends.begin(), ends.end());
  // partner[end] = the other segment end on the same edge, or -1.
  std::vector<int> partner(segs.size() * 2, -1);
  for (size_t k = 0; k + 1 < ends.size(); ++k)
    if (ends[k].first == ends[k + 1].first) {
      partner[ends[k].second] = ends[k + 1].second;
      partner[ends[k + 1].second] = ends[k].second;
      ++k;
    }
  std::vector<char> used(segs.size(), 0);
  // Walks from segment end `start_end` through its segment and on, appending points.
  auto walk = [&](int start_end, ContourLine& line) {
    int end = start_end;
    for (;;) {
      const int s = end / 2;
      if (used[s]) {
        line.closed = true;
        return;
      }
      used[s] = 1;
      const int other = end ^ 1;
      line.points.push_back(segs[s].point[other & 1]);
      end = partner[other];
      if (end < 0) return;
    }
  };
  // Open lines first, from an end without a partner; then what is left are closed loops.
  for (int pass = 0; pass < 2; ++pass)
    for (size_t s = 0; s < segs.size(); ++s) {
      if (used[s]) continue;
      const int start = static_cast<int>(s * 2);
      if (pass == 0 && partner[start] >= 0 && partner[start + 1] >= 0) continue;
      const int from = pass == 0 && partner[start] >= 0 ? start + 1 : start;
      ContourLine line;
      line.level = level;
      line.points.push_back(segs[s].point[from & 1]);
      walk(from, line);
      if (pass == 1) line.closed = true;
      out->push_back(std::move(line));
    }
}

}  // namespace

void landscape_contours(const LandscapeGrid& grid, std::span<const double> levels,
                        std::vector<ContourLine>* out) {
  out->clear();
  const int n1 = grid.n1, n2 = grid.n2;
  // Grid edges: horizontal (i, j)-(i+1, j) is 2 (i + n1 j), vertical (i, j)-(i, j+1) is that + 1.
  auto h_edge = [n1](int i, int j) { return 2L * (i + static_cast<long>(n1) * j); };
  auto v_edge = [n1](int i, int j) { return 2L * (i + static_cast<long>(n1) * j) + 1; };
  std::vector<Segment> segs;
  for (double level : levels) {
    segs.clear();
    for (int j = 0; j + 1 < n2; ++j)
      for (int i = 0; i + 1 < n1; ++i) {
        // Corners counter-clockwise from the bottom left: a (i,j), b (i+1,j), c (i+1,j+1), d
        // (i,j+1).
        const double a = grid.at(i, j), b = grid.at(i + 1, j), c = grid.at(i + 1, j + 1),
                     d = grid.at(i, j + 1);
        if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && std::isfinite(d)))
          continue;
        const int code = (a >= level) | (b >= level) << 1 | (c >= level) << 2 | (d >= level) << 3;
        if (code == 0 || code == 15) continue;
        const double x0 = grid.s1(i), x1 = grid.s1(i + 1), y0 = grid.s2(j), y1 = grid.s2(j + 1);
        auto lerp = [level](double p, double q) { return (level - p) / (q - p); };
        // Cell edges 0 bottom (a-b), 1 right (b-c), 2 top (d-c), 3 left (a-d).
        auto edge_point = [&](int e) -> std::pair<long, SigmaPair> {
          switch (e) {
            case 0:
              return {h_edge(i, j), {x0 + lerp(a, b) * (x1 - x0), y0}};
            case 1:
              return {v_edge(i + 1, j), {x1, y0 + lerp(b, c) * (y1 - y0)}};
            case 2:
              return {h_edge(i, j + 1), {x0 + lerp(d, c) * (x1 - x0), y1}};
            default:
              return {v_edge(i, j), {x0, y0 + lerp(a, d) * (y1 - y0)}};
          }
        };
        auto add = [&](int e0, int e1) {
          const auto p = edge_point(e0), q = edge_point(e1);
          segs.push_back(Segment{{p.first, q.first}, {p.second, q.second}});
        };
        const bool centre_above = 0.25 * (a + b + c + d) >= level;
        switch (code) {
          case 1:
          case 14:
            add(3, 0);
            break;
          case 2:
          case 13:
            add(0, 1);
            break;
          case 3:
          case 12:
            add(3, 1);
            break;
          case 4:
          case 11:
            add(1, 2);
            break;
          case 6:
          case 9:
            add(0, 2);
            break;
          case 7:
          case 8:
            add(3, 2);
            break;
          case 5:  // a and c above
            if (centre_above) {
              add(0, 1);
              add(2, 3);
            } else {
              add(3, 0);
              add(1, 2);
            }
            break;
          case 10:  // b and d above
            if (centre_above) {
              add(3, 0);
              add(1, 2);
            } else {
              add(0, 1);
              add(2, 3);
            }
            break;
          default:
            break;
        }
      }
    chain_segments(segs, level, out);
  }
}

void triangle_sigmas(const Simulation& sim, std::vector<SigmaPair>* out) {
  const int n = sim.mesh.triangle_count();
  out->resize(static_cast<size_t>(n));
  for (int t = 0; t < n; ++t) {
    const Vec2 s = polar_svd(triangle_deformation_gradient(sim, t)).sigma;
    (*out)[static_cast<size_t>(t)] = {s(0), s(1)};
  }
}

bool update_landscape_cache(Model model, const Lame& lame, const LandscapeDomain& domain,
                            int per_unit, LandscapeCache* cache) {
  if (cache->valid && cache->grid.model == model && cache->grid.lame == lame &&
      cache->grid.domain == domain && cache->per_unit == per_unit)
    return false;
  build_landscape_grid(model, lame, domain, per_unit, &cache->grid);
  cache->per_unit = per_unit;
  cache->scale = landscape_scale(lame);
  cache->levels = landscape_contour_levels(cache->scale);
  landscape_contours(cache->grid, cache->levels, &cache->contours);
  cache->valid = true;
  ++cache->rebuilds;
  return true;
}

}  // namespace invfree
