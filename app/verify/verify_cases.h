// The benchmark cases of `invfree verify` (docs/verification.md): each a static scene of
// assets/scenes/verify/ (verify_scenes.h), a series of meshes to run it on, the one number
// it measures and the exact or reference value that number must approach
// (reference_solutions.h).
//
//   patch                every triangle's F against the applied homogeneous stretch
//   cantilever           tip deflection v(L, 0) against the clamped beam's converged value
//                        (Timoshenko's beam theory is 0.34% above it)
//   kirsch               peak hoop stress at the hole's top / the gross-section stress
//                        against Heywood's finite-width factor (quarter plate, symmetry)
//   cook                 v at the loaded edge's midpoint (48, 52) against the literature
//   cook-incompressible  the same at nu = 0.4999 (linear triangles lock)
//   large-strain         the stretch of every triangle at every load step against the
//                        closed-form plane-strain uniaxial neo-Hookean curve, up to 3
//
// A mesh level is an n_seg: the shapes' max_edge is their bounding box's longer side /
// n_seg (docs/shapes.md). Kirsch's hole is a polygon whose points follow the level
// (kirsch_quarter_outline), so the circle refines with the mesh.
// Inputs: a case and an n_seg. Outputs: the scene, and one run's measurement.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace invfree {

enum class VerifyCaseKind { Patch, Cantilever, Kirsch, Cook, CookIncompressible, LargeStrain };

struct VerifyCase {
  VerifyCaseKind kind;
  std::string name;       // the scene file's stem and the --cases word, e.g. "cantilever"
  std::string label;      // for the chart's legend, e.g. "cantilever: tip deflection"
  std::string quantity;   // what `computed` is, with its unit
  std::string reference;  // what `reference` is
  // The theoretical slope of log(relative error) against log(unknowns): -1 for a
  // displacement (error O(h^2) with linear triangles, unknowns ~ h^-2), -0.5 for a
  // recovered stress (O(h)). NaN for the exact cases (patch, large-strain): their error is
  // rounding, at every mesh.
  double expected_slope;
  std::vector<int> levels;        // n_seg of each mesh, coarse to fine
  std::vector<int> quick_levels;  // the same under --quick
};

// Every case, in the order of the table and the chart.
const std::vector<VerifyCase>& verify_cases();
const VerifyCase* find_verify_case(std::string_view name);  // nullptr when none
std::string verify_case_names();                            // "patch, cantilever, ..."
bool verify_case_is_exact(const VerifyCase& c);             // no expected slope

// Kirsch's quarter plate: x in [0, 2], y in [0, 1] (a 4 x 2 strip, width W = 2, cut along
// its symmetry lines), a hole of radius 0.2 at the origin (d / W = 0.2).
inline constexpr double kKirschHoleRadius = 0.2;
inline constexpr double kKirschHalfLength = 2.0;
inline constexpr double kKirschHalfWidth = 1.0;
// The quarter arc's segments at mesh level n_seg: 6 n_seg, so a segment (pi a / (12 n_seg))
// is 1/38 of the plate's max_edge (2 / n_seg) and the mesher grades the mesh down to it
// around the hole; the hole's polygon refines with the mesh. (Coarser arcs leave the stress
// gradient at the hole, 7 sigma / a, to a few triangles whose layout changes from mesh to
// mesh: the recovered peak then converges erratically; docs/verification.md.)
int kirsch_arc_segments(int n_seg);
// The outline, counter-clockwise from (a, 0): (a, 0), (2, 0), (2, 1), (0, 1), (0, a), then
// the arc's points back towards (a, 0). Its points on the circle are exact to rounding;
// (0, a), where the hoop stress peaks, is a node of every mesh.
Loop kirsch_quarter_outline(int n_seg);

// The case's scene at mesh level n_seg, from its embedded file; nullopt and `error` when the
// file does not parse or the level makes it invalid.
std::optional<SceneDef> verify_case_scene(const VerifyCase& c, int n_seg, std::string* error);

// One point of the large-strain load path: the load step's applied nominal stress, the
// stretch along the load computed (the mean over the triangles) and in closed form.
struct LoadPathPoint {
  double nominal_stress = 0.0;  // Pa
  double stretch = 0.0;
  double exact_stretch = 0.0;
};

// One run of a case on one mesh.
struct CaseRun {
  int unknowns = 0;  // free degrees of freedom: 2 x nodes - held coordinates
  int triangles = 0;
  double max_edge = 0.0;  // the mesher's target edge length (m)
  double computed = 0.0;
  double reference = 0.0;
  // |computed - reference| / |reference|; patch: the largest entry of |F - F*| over every
  // triangle / the largest entry of F*; large-strain: the largest relative error of either
  // principal stretch (and the shear entries of F) over every triangle and load step.
  double relative_error = 0.0;
  int load_steps = 0;
  int newton_iterations = 0;        // summed over the load steps
  int max_newton_iterations = 0;    // of one load step
  double solve_ms = 0.0;            // the steps' wall time (meshing and setup excluded)
  std::vector<LoadPathPoint> path;  // large-strain only: one per load step
  std::string failure;              // "" when every step converged and the measure was taken
};

// Builds the simulation, steps it through every load step (scene.ramp_steps, at least one)
// and measures. Never throws for a failed step: `failure` says which and why.
CaseRun run_verify_case(const VerifyCase& c, const SceneDef& scene);

}  // namespace invfree
