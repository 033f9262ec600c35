#include "app/verify/verify_cases.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "app/verify/reference_solutions.h"
#include "app/verify/verify_scenes.h"
#include "scene/fixed_nodes.h"
#include "scene_io/scene_file.h"
#include "shape/shape_region.h"
#include "simulation.h"
#include "triangle_fields.h"

namespace invfree {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The levels: each doubles n_seg (a quarter of the edge length squared: four times the
// unknowns), from a mesh where the answer is already in the asymptotic range to one of
// some 20,000 to 50,000 triangles (a second or so each); --quick stops two levels earlier.
const std::vector<VerifyCase>& cases() {
  static const std::vector<VerifyCase> c = {
      {VerifyCaseKind::Patch,
       "patch",
       "patch test: max |F - F*|",
       "max over triangles of max |F_ij - F*_ij| (F* = diag(1.2, 0.9))",
       "0 (exact)",
       kNaN,
       {4, 8, 16, 32, 64},
       {4, 8, 16}},
      {VerifyCaseKind::Cantilever,
       "cantilever",
       "cantilever: tip deflection",
       "tip deflection -v(L, 0) (m)",
       "the clamped beam's converged 3658.8 P/E (Timoshenko's beam is 0.34% above)",
       -1.0,
       {10, 20, 40, 80, 160, 320},
       {10, 20, 40, 80}},
      {VerifyCaseKind::Kirsch,
       "kirsch",
       "Kirsch: peak hoop stress",
       "sigma_xx(0, a) / gross-section stress (nodal average)",
       "Heywood's finite-width factor, d/W = 0.2",
       -0.5,
       {8, 16, 32, 64, 128, 256},
       {8, 16, 32}},
      {VerifyCaseKind::Cook,
       "cook",
       "Cook's membrane: v(48, 52)",
       "v(48, 52) (m)",
       "23.96 F / E (plane stress, nu = 1/3)",
       -1.0,
       {4, 8, 16, 32, 64, 128},
       {4, 8, 16, 32}},
      {VerifyCaseKind::CookIncompressible,
       "cook-incompressible",
       "Cook's membrane, \u03bd = 0.4999: v(48, 52)",
       "v(48, 52) (m)",
       "18.512 F / E (converged mixed elements)",
       -1.0,
       {4, 8, 16, 32, 64, 128},
       {4, 8, 16, 32}},
      {VerifyCaseKind::LargeStrain,
       "large-strain",
       "large strain: stretch up to 3",
       "stretch along the load at the last load step (mean over triangles)",
       "plane-strain uniaxial neo-Hookean, closed form",
       kNaN,
       {2, 4, 8, 16},
       {2, 4}},
  };
  return c;
}

// Rest-space bounding box of the mesh.
struct RestBox {
  Vec2 lo, hi;
};
RestBox rest_box(const Mesh& mesh) {
  RestBox b{Vec2::Constant(INFINITY), Vec2::Constant(-INFINITY)};
  for (const Vec2& p : mesh.rest) {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  return b;
}

// The displacement at rest point X, interpolated linearly in the triangle that contains it
// (barycentric coordinates in rest space; on an edge either neighbour gives the same value).
// nullopt when no triangle contains X.
std::optional<Vec2> displacement_at(const Simulation& sim, const Vec2& X) {
  const Mesh& m = sim.mesh;
  const RestBox box = rest_box(m);
  const double tol = 1e-12 * (box.hi - box.lo).maxCoeff();
  for (int t = 0; t < m.triangle_count(); ++t) {
    const auto& tri = m.triangles[t];
    const Vec2 a = m.rest[tri[0]], b = m.rest[tri[1]], c = m.rest[tri[2]];
    const double area2 = (b - a).x() * (c - a).y() - (c - a).x() * (b - a).y();
    const double l1 = ((b - X).x() * (c - X).y() - (c - X).x() * (b - X).y()) / area2;
    const double l2 = ((c - X).x() * (a - X).y() - (a - X).x() * (c - X).y()) / area2;
    const double l3 = 1.0 - l1 - l2;
    const double scale = std::sqrt(std::abs(area2));
    if (std::min({l1, l2, l3}) * scale < -tol) continue;
    Vec2 u = Vec2::Zero();
    const double w[3] = {l1, l2, l3};
    for (int k = 0; k < 3; ++k) u += w[k] * (sim.x.segment<2>(2 * tri[k]) - m.rest[tri[k]]);
    return u;
  }
  return std::nullopt;
}

// The node at rest point X (within rounding of the mesh's size), or -1.
int node_at(const Mesh& mesh, const Vec2& X) {
  const RestBox box = rest_box(mesh);
  const double tol = 1e-9 * (box.hi - box.lo).maxCoeff();
  for (int i = 0; i < mesh.node_count(); ++i)
    if ((mesh.rest[i] - X).lpNorm<Eigen::Infinity>() <= tol) return i;
  return -1;
}

// The Cauchy stress at a node recovered by averaging its triangles' (constant) Cauchy
// stresses weighted by their rest areas.
Mat2 nodal_cauchy(const Simulation& sim, int node) {
  Mat2 sum = Mat2::Zero();
  double area = 0.0;
  for (int t = 0; t < sim.mesh.triangle_count(); ++t) {
    const auto& tri = sim.mesh.triangles[t];
    if (tri[0] != node && tri[1] != node && tri[2] != node) continue;
    sum += sim.mesh.rest_area[t] * analyze_triangle(sim, t).cauchy;
    area += sim.mesh.rest_area[t];
  }
  return area > 0.0 ? Mat2(sum / area) : Mat2::Constant(kNaN);
}

double relative(double computed, double reference) {
  return std::abs(computed - reference) / std::abs(reference);
}

// E and nu of the scene's (single) material.
void scene_young_poisson(const SceneDef& s, double* youngs, double* poisson) {
  young_poisson_from_lame(s.lame, youngs, poisson);
}

// The measurements, after every load step converged. Each sets computed, reference and
// relative_error, or failure.
void measure_patch(const Simulation& sim, CaseRun& r) {
  const Vec2 s = sim.scene.initial_stretch;
  const Mat2 exact = s.asDiagonal();
  double worst = 0.0;
  for (int t = 0; t < sim.mesh.triangle_count(); ++t)
    worst =
        std::max(worst, (triangle_deformation_gradient(sim, t) - exact).lpNorm<Eigen::Infinity>());
  r.computed = worst;
  r.reference = 0.0;
  r.relative_error = worst / exact.lpNorm<Eigen::Infinity>();
}

// The fully clamped cantilever of cantilever.toml (L/H = 10, nu = 0.3, uniform end shear)
// has no closed form: its tip deflection v E / P, converged with Taylor-Hood elements
// (docs/verification.md, "Cantilever"; linear triangles up to 205,000 triangles,
// Richardson-extrapolated, give 3658.7). Timoshenko's beam (3671.2) is 0.34% above it: the
// clamp stops the end section's shear warping, which beam theory lets it have.
constexpr double kClampedCantileverTipDeflection = 3658.8;

// Clamped at the left end (min x), loaded at the right end: the tip is the right end's
// mid-depth point.
void measure_cantilever(const Simulation& sim, CaseRun& r) {
  const RestBox box = rest_box(sim.mesh);
  const double L = box.hi.x() - box.lo.x(), H = box.hi.y() - box.lo.y();
  const double P = -sim.scene.tractions.at(0).force.y();
  double E, nu;
  scene_young_poisson(sim.scene, &E, &nu);
  if (std::abs(L / H - 10.0) > 1e-9 || std::abs(nu - 0.3) > 1e-9) {
    r.failure = "the reference is for L/H = 10 and nu = 0.3";
    return;
  }
  const auto u = displacement_at(sim, Vec2(box.hi.x(), 0.5 * (box.lo.y() + box.hi.y())));
  if (!u) {
    r.failure = "no triangle holds the tip";
    return;
  }
  r.computed = -u->y();
  r.reference = kClampedCantileverTipDeflection * P / E;
  r.relative_error = relative(r.computed, r.reference);
}

void measure_kirsch(const Simulation& sim, CaseRun& r) {
  const int top = node_at(sim.mesh, Vec2(0.0, kKirschHoleRadius));
  if (top < 0) {
    r.failure = "no node at the hole's top (0, a)";
    return;
  }
  const double gross = sim.scene.tractions.at(0).force.x() / kKirschHalfWidth;
  r.computed = nodal_cauchy(sim, top)(0, 0) / gross;
  r.reference = hole_in_strip_stress_factor(kKirschHoleRadius / kKirschHalfWidth);
  r.relative_error = relative(r.computed, r.reference);
}

void measure_cook(const Simulation& sim, bool incompressible, CaseRun& r) {
  const double F = sim.scene.tractions.at(0).force.y();
  double E, nu;
  scene_young_poisson(sim.scene, &E, &nu);
  const auto u = displacement_at(sim, cook_membrane_point(CookPoint::MidEdge));
  if (!u) {
    r.failure = "no triangle holds (48, 52)";
    return;
  }
  r.computed = u->y();
  if (incompressible) {
    if (std::abs(nu - kCookIncompressiblePoisson) > 1e-9) {
      r.failure = "the reference is for nu = 0.4999";
      return;
    }
    r.reference = cook_membrane_incompressible_reference_tip_v(CookPoint::MidEdge, F, E);
  } else {
    // The scene's plane-strain E*, nu* back to the classic plane-stress E, nu
    // (cook_membrane_plane_strain_material's inverse: nu = nu* / (1 - nu*)).
    const double nu_ps = nu / (1.0 - nu);
    const double E_ps = E * (1.0 + nu_ps) * (1.0 + nu_ps) / (1.0 + 2.0 * nu_ps);
    if (std::abs(nu_ps - 1.0 / 3.0) > 1e-9) {
      r.failure = "the reference is for plane-stress nu = 1/3 (plane-strain nu* = 0.25)";
      return;
    }
    r.reference = cook_membrane_reference_tip_v(CookPoint::MidEdge, F, E_ps);
  }
  r.relative_error = relative(r.computed, r.reference);
}

// After load step `k`: the closed form at that step's nominal stress against every
// triangle's F. Adds a path point and keeps the worst error in r.relative_error.
void measure_large_strain_step(const Simulation& sim, long k, CaseRun& r) {
  const RestBox box = rest_box(sim.mesh);
  const double H = box.hi.y() - box.lo.y();
  const double P = load_factor(sim.scene, k) * sim.scene.tractions.at(0).force.x() / H;
  const double a = uniaxial_stretch_for_stress(P, sim.scene.lame.mu, sim.scene.lame.lambda);
  const double b = uniaxial_lateral_stretch(a, sim.scene.lame.mu, sim.scene.lame.lambda);
  double mean = 0.0;
  for (int t = 0; t < sim.mesh.triangle_count(); ++t) {
    const Mat2 F = triangle_deformation_gradient(sim, t);
    mean += F(0, 0);
    r.relative_error =
        std::max({r.relative_error, std::abs(F(0, 0) - a) / a, std::abs(F(1, 1) - b) / b,
                  std::abs(F(0, 1)) / a, std::abs(F(1, 0)) / a});
  }
  mean /= sim.mesh.triangle_count();
  r.path.push_back({P, mean, a});
  r.computed = mean;
  r.reference = a;
}

}  // namespace

const std::vector<VerifyCase>& verify_cases() {
  return cases();
}

const VerifyCase* find_verify_case(std::string_view name) {
  for (const VerifyCase& c : cases())
    if (c.name == name) return &c;
  return nullptr;
}

std::string verify_case_names() {
  std::string s;
  for (const VerifyCase& c : cases()) s += (s.empty() ? "" : ", ") + c.name;
  return s;
}

bool verify_case_is_exact(const VerifyCase& c) {
  return std::isnan(c.expected_slope);
}

int kirsch_arc_segments(int n_seg) {
  return 6 * n_seg;
}

Loop kirsch_quarter_outline(int n_seg) {
  const double a = kKirschHoleRadius;
  Loop outline = {Vec2(a, 0.0), Vec2(kKirschHalfLength, 0.0),
                  Vec2(kKirschHalfLength, kKirschHalfWidth), Vec2(0.0, kKirschHalfWidth),
                  Vec2(0.0, a)};
  const int m = kirsch_arc_segments(n_seg);
  // From the top (k = m - 1) down towards (a, 0) (k = 1): the points at angle k pi / (2m).
  for (int k = m - 1; k >= 1; --k) {
    const double t = 0.5 * std::numbers::pi * k / m;
    outline.push_back(Vec2(a * std::cos(t), a * std::sin(t)));
  }
  return outline;
}

std::optional<SceneDef> verify_case_scene(const VerifyCase& c, int n_seg, std::string* error) {
  std::string_view text;
  for (const EmbeddedScene& e : verify_scene_files())
    if (e.name == c.name) text = e.text;
  if (text.empty()) {
    *error = "verify scene " + c.name + ".toml is not embedded in this build";
    return std::nullopt;
  }
  SceneLoad load = parse_scene_toml(text, "assets/scenes/verify/" + c.name + ".toml");
  if (!load.scene) {
    *error = load.error;
    return std::nullopt;
  }
  SceneDef scene = *load.scene;
  scene.n_seg = n_seg;
  if (c.kind == VerifyCaseKind::Kirsch) scene.shape.outline = kirsch_quarter_outline(n_seg);
  if (const std::string e = validate_scene(scene); !e.empty()) {
    *error = c.name + " at n_seg " + std::to_string(n_seg) + ": " + e;
    return std::nullopt;
  }
  return scene;
}

CaseRun run_verify_case(const VerifyCase& c, const SceneDef& scene) {
  CaseRun r;
  Simulation sim = make_simulation(scene);
  r.triangles = sim.mesh.triangle_count();
  r.unknowns =
      2 * sim.mesh.node_count() - static_cast<int>(select_fixed_dofs(scene, sim.mesh).size());
  r.max_edge = scene.shape.kind == ShapeKind::Square ? scene.side / scene.n_seg
                                                     : shape_max_edge(scene.shape, scene.n_seg);
  r.computed = r.reference = r.relative_error = kNaN;
  if (c.kind == VerifyCaseKind::LargeStrain) r.relative_error = 0.0;
  const long steps = std::max(1, scene.ramp_steps);
  for (long k = 1; k <= steps; ++k) {
    const StepReport report = step(sim);
    r.solve_ms += report.wall_ms;
    r.newton_iterations += report.newton_iterations;
    r.max_newton_iterations = std::max(r.max_newton_iterations, report.newton_iterations);
    ++r.load_steps;
    if (report.status != StepStatus::Ok) {
      r.failure = "load step " + std::to_string(k) + ": " + step_status_name(report.status) +
                  (report.message.empty() ? "" : ": " + report.message);
      r.computed = r.reference = r.relative_error = kNaN;
      return r;
    }
    if (c.kind == VerifyCaseKind::LargeStrain) measure_large_strain_step(sim, k, r);
  }
  switch (c.kind) {
    case VerifyCaseKind::Patch:
      measure_patch(sim, r);
      break;
    case VerifyCaseKind::Cantilever:
      measure_cantilever(sim, r);
      break;
    case VerifyCaseKind::Kirsch:
      measure_kirsch(sim, r);
      break;
    case VerifyCaseKind::Cook:
    case VerifyCaseKind::CookIncompressible:
      measure_cook(sim, c.kind == VerifyCaseKind::CookIncompressible, r);
      break;
    case VerifyCaseKind::LargeStrain:
      break;
  }
  return r;
}

}  // namespace invfree
