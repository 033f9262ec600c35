// A scene: a plain definition struct with defaults (the reference demo, `compress`), the
// range of each of its values, and its validation. A term whose `has_*` flag is false is
// never evaluated (a missing TOML section switches it off). The built-in scenes are TOML
// files (assets/scenes/), read by the scene_io library.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "enum_names.h"
#include "linalg/linear_solver_kind.h"
#include "material/material.h"
#include "scene/mesh.h"
#include "shape/shape.h"

namespace invfree {

// Static: each step minimises the potential without inertia (elastic energy, gravity,
// boundary loads, barriers): equilibrium under the loads of that step's ramp.
enum class Integrator { ImplicitEuler, SymplecticEuler, Static };
inline constexpr EnumName<Integrator> kIntegratorNames[] = {
    {Integrator::ImplicitEuler, "implicit-euler"},
    {Integrator::SymplecticEuler, "symplectic-euler"},
    {Integrator::Static, "static"}};
const char* integrator_name(Integrator i);
std::optional<Integrator> integrator_from_name(std::string_view name);

// Named corners of the rest mesh's bounding box that a scene holds fixed (a bit each).
enum class FixedCorners : unsigned {
  None = 0,
  BottomLeft = 1,
  BottomRight = 2,
  TopLeft = 4,
  TopRight = 8,
  Bottom = 3,
  Top = 12,
  Left = 5,
  Right = 10,
  All = 15
};
inline constexpr EnumName<FixedCorners> kFixedCornersNames[] = {
    {FixedCorners::None, "none"},
    {FixedCorners::TopLeft, "top-left"},
    {FixedCorners::TopRight, "top-right"},
    {FixedCorners::BottomLeft, "bottom-left"},
    {FixedCorners::BottomRight, "bottom-right"},
    {FixedCorners::Top, "top"},
    {FixedCorners::Bottom, "bottom"},
    {FixedCorners::Left, "left"},
    {FixedCorners::Right, "right"},
    {FixedCorners::All, "all"},
};
const char* fixed_corners_name(FixedCorners c);
std::optional<FixedCorners> fixed_corners_from_name(std::string_view name);

// Which coordinates of the fixed nodes are held: both, or only x or y (a roller support).
enum class FixedComponents { XY, X, Y };
inline constexpr EnumName<FixedComponents> kFixedComponentsNames[] = {
    {FixedComponents::XY, "xy"}, {FixedComponents::X, "x"}, {FixedComponents::Y, "y"}};

// [traction] or [[traction]]: a load on the boundary edges whose two nodes lie (at rest) in
// [box_min, box_max]. `force`: a dead load, the total force (N per unit thickness) spread
// over those edges by length. `pressure` (Pa): a follower load normal to the deformed edges,
// pushing into the body; the edges must then form whole boundary loops (on them it is
// conservative: pressure times the enclosed area). scene/tractions.h.
struct TractionDef {
  Vec2 box_min = Vec2(1.0, 1.0);
  Vec2 box_max = Vec2(-1.0, -1.0);
  Vec2 force = Vec2::Zero();
  double pressure = 0.0;
  bool operator==(const TractionDef&) const = default;
};
// The largest number of [[traction]] tables a scene may list.
constexpr int kMaxTractions = 64;

// [mass_spring] law: the spring's energy (potential/mass_spring.h). Green: the course's
// chapter 1, E = 1/2 k l^2 (|d|^2/l^2 - 1)^2; Hooke: chapter 0's linear spring,
// E = 1/2 k (|d| - l)^2.
enum class SpringLaw { Green, Hooke };
inline constexpr EnumName<SpringLaw> kSpringLawNames[] = {{SpringLaw::Green, "green"},
                                                          {SpringLaw::Hooke, "hooke"}};

// [reduced] basis: Newton's step restricted to a subspace, x = x^0 + B q (the course's
// chapter 9; scene/reduced_basis.h). Full: no reduction.
enum class ReducedBasis { Full, Polynomial, Modal };
inline constexpr EnumName<ReducedBasis> kReducedBasisNames[] = {
    {ReducedBasis::Full, "full"}, {ReducedBasis::Polynomial, "polynomial"},
    {ReducedBasis::Modal, "modal"}};

// [modes] element: the elements of `invfree modes`' linear modal analysis
// (modal/modal_analysis.h): linear triangles on the scene's own mesh, or bilinear quads
// (2 x 2 Gauss, as the course's linear.py) from the mesh's triangle pairs.
enum class ModalElement { Triangle, Quad };
inline constexpr EnumName<ModalElement> kModalElementNames[] = {
    {ModalElement::Triangle, "triangle"}, {ModalElement::Quad, "quad"}};

// [mesh] mass (scene/mesh.h's MassMode), as a scene file spells it.
inline constexpr EnumName<MassMode> kMassModeNames[] = {{MassMode::Uniform, "uniform"},
                                                        {MassMode::Lumped, "lumped"}};

// [[body]]: one body of a scene with several bodies. An unset value takes the scene's:
// [mesh] shape keys, side and n_seg, [initial] velocity, [material]. The body's own frame
// (a square's or disk's centre, a polygon's origin) sits at `offset` at rest (the scene's
// single body is at the origin).
struct BodyDef {
  std::optional<double> side;
  std::optional<int> n_seg;
  std::optional<ShapeKind> shape;
  std::optional<double> width, height, radius, inner_radius, scale, max_edge;
  std::optional<Loop> outline;
  std::optional<std::vector<Loop>> holes;
  std::optional<std::string> file, path_id;
  ShapeFile loaded;  // from this body's `file` (scene_io); unused when it gives none
  Vec2 offset = Vec2::Zero();
  std::optional<Vec2> velocity;
  std::optional<Lame> lame;
  bool operator==(const BodyDef&) const = default;
};

// A body with every default filled in from its scene.
struct PlacedBody {
  double side = 1.0;
  int n_seg = 4;
  ShapeDef shape;  // the body's shape keys, its own or the scene's [mesh]
  Vec2 offset = Vec2::Zero();
  Vec2 velocity = Vec2::Zero();
  Lame lame;
};

struct SceneDef {
  std::string name = "compress";
  // [mesh]
  double side = 1.0;
  int n_seg = 4;
  double density = 1000.0;
  MassMode mass = MassMode::Uniform;
  // Every node's mass (kg) when > 0 (the course's chapter 0: 1000 kg particles); 0: from
  // density and `mass`.
  double node_mass = 0.0;
  double jitter = 0.0;  // random initial node displacement, as a fraction of the edge length
  std::uint64_t seed = 1;
  // [mesh] shape, width, height, radius, inner_radius, outline, holes, file, path_id, scale,
  // max_edge: the body's shape (shape/shape.h); "square" is the side x n_seg grid.
  ShapeDef shape;
  // [material]
  Model model = Model::NeoHookean;
  Lame lame = lame_from_young_poisson(1e5, 0.4);
  // [time]
  double h = 0.01;
  double tol = 1e-2;  // Newton stops when |p|_inf / h < tol (m/s)
  int max_newton = 100;
  // Loads (gravity, tractions) grow linearly over the first ramp_steps steps, then stay:
  // step k (1-based) applies min(1, k / ramp_steps) of them.
  int ramp_steps = 1;
  // [solver]
  HessianProjection projection = HessianProjection::Diagonal;
  bool inversion_filter = true;
  Integrator integrator = Integrator::ImplicitEuler;
  LinearSolverKind linear_solver = LinearSolverKind::Auto;  // see core/linear_solver_kind.h
  bool step_expansion = true;                               // Newton's safeguards, core/newton.h
  bool friction_crossing_stop = true;
  // [initial]
  Vec2 initial_velocity = Vec2::Zero();
  // [gravity]
  bool has_gravity = true;
  Vec2 gravity = Vec2(0.0, -9.81);
  // [ground]
  bool has_ground = true;
  double ground_y = -1.0;
  double friction = 0.11;
  // [ceiling]
  bool has_ceiling = true;
  double ceiling_y = 0.6;
  double ceiling_velocity = -0.5;
  double ceiling_stop = -0.7;  // stops once its start-of-step height is at or below this
  // [barrier]
  double dhat = 0.01;
  double kappa = 1e5;
  // The course's additions (solid-sim-tutorial chapters 1-5), each off by default.
  // [mass_spring]: springs on the mesh's edges and both diagonals of every cell
  // (potential/mass_spring.h) instead of the triangles' elasticity.
  bool has_mass_spring = false;
  double spring_stiffness = 1e5;  // k (N/m)
  SpringLaw spring_law = SpringLaw::Green;
  // Node index pairs; empty: the mesh's edges and both diagonals of every cell.
  std::vector<std::array<int, 2>> springs;
  // [gravity] per_spring: gravity added to a node once per spring it ends (the course's
  // chapter 0 simulator2.py adds it inside its spring loop); false: once per node.
  bool gravity_per_spring = false;
  // [fixed]: nodes held at their initial positions (Dirichlet, eliminated by the solver),
  // chosen by rules in rest space over all nodes: corners of the rest bounding box and/or
  // the nodes inside a box (an empty box, min > max, selects none). scene/fixed_nodes.h.
  bool has_fixed = false;
  FixedCorners fixed_corners = FixedCorners::None;
  Vec2 fixed_box_min = Vec2(1.0, 1.0);
  Vec2 fixed_box_max = Vec2(-1.0, -1.0);
  // More boxes, each [[x_min, y_min], [x_max, y_max]] (a plate held at both ends).
  std::vector<Loop> fixed_boxes;
  // Of the nodes above (corners, box, boxes): both coordinates held, or only x or y.
  FixedComponents fixed_components = FixedComponents::XY;
  // Rollers: boxes whose nodes are held in x only (a wall's symmetry line) or in y only.
  std::vector<Loop> fixed_x_boxes, fixed_y_boxes;
  // [traction] / [[traction]]: boundary loads, none by default.
  std::vector<TractionDef> tractions;
  // The ground's normal (any slope; normalised where used): the plane passes through
  // (0, ground_y). (0, 1) is the horizontal ground.
  Vec2 ground_normal = Vec2(0.0, 1.0);
  // [initial] stretch: rest positions scaled by (sx, sy) about the origin at t = 0.
  Vec2 initial_stretch = Vec2(1.0, 1.0);
  // [self_contact]: IPC point-edge barrier between boundary nodes and edges of every body
  // (potential/self_contact_barrier.h), CCD in the line search, the intersection invariant.
  // On by default (SceneDef{}; a scene file without the section: self_contact_by_default);
  // `enabled = false` switches it off. It runs where it can: self_contact_on() below.
  bool has_self_contact = true;
  double self_friction = 0.0;    // point-edge friction coefficient (potential/self_friction.h)
  bool self_contact_ccd = true;  // false: the line search's CCD filter is off (a study row)
  // [reduced]: the subspace of Newton's steps; `order` 1-3 of the polynomial basis (1:
  // affine), `modes` eigenvectors of the rest-shape Hessian for the modal one.
  ReducedBasis reduced_basis = ReducedBasis::Full;
  int reduced_order = 1;
  int reduced_modes = 6;
  // [modes] element: what `invfree modes` discretises (its --element overrides).
  ModalElement modes_element = ModalElement::Triangle;
  // [[body]]: the scene's bodies, in node order. Empty: one body, the [mesh] square at the
  // origin (every scene file without [[body]] tables).
  std::vector<BodyDef> bodies;

  bool operator==(const SceneDef&) const = default;
  // The plane barriers' contact area per node, the first body's side / n_seg (every body's
  // when they share it; otherwise scene_node_contact_areas gives each node its body's).
  double contact_area() const;
  bool has_contact() const { return has_ground || has_ceiling; }
  bool has_tractions() const { return !tractions.empty(); }
  // Self-contact runs in this scene's steps: asked for and able to (self_contact_can_run).
  // With symplectic Euler that is the intersection invariant alone (no contact force).
  bool self_contact_on() const;
  bool is_static() const { return integrator == Integrator::Static; }
  // The triangles' elasticity (material.*) is a term of this scene's potential.
  bool has_triangle_elasticity() const { return !has_mass_spring; }
};

int body_count(const SceneDef& s);  // 1 without [[body]] tables
// Self-contact can run in this scene: not with [mass_spring] or [fixed] (their precomputed
// slots need the fixed Hessian pattern that contact grows). A scene file or --set that asks
// for it there is refused (scene_io); a term switched on later leaves it inactive.
bool self_contact_can_run(const SceneDef& s);
// Its default in a scene file without [self_contact]: on where it can run, except with
// symplectic Euler, which has no contact force (its invariant alone would stop a run that
// passes through itself, where such a scene ran on before self-contact was on by default).
bool self_contact_by_default(const SceneDef& s);
// The fraction of the loads step `step` (1-based) applies: min(1, step / ramp_steps).
double load_factor(const SceneDef& s, long step);
PlacedBody placed_body(const SceneDef& s, int body);
// The body's edge length: side / n_seg for the square, the target max_edge of any other
// shape (shape/shape_mesh.h's shape_max_edge).
double body_edge_length(const SceneDef& s, int body);
// One material for every body (the live sliders): the scene's, and no body's own.
void set_material_of_every_body(SceneDef& s, const Lame& lame);
// The largest number of [[body]] tables a scene may list.
constexpr int kMaxBodies = 64;

// The ground's unit normal, and a point's signed distance to the ground plane through
// (0, ground_y); exactly y - ground_y for the horizontal ground.
Vec2 ground_unit_normal(const SceneDef& s);
// False for the horizontal ground (normal (0, +y)), which keeps its own arithmetic.
bool ground_is_sloped(const SceneDef& s);
double ground_gap(const SceneDef& s, double x, double y);

// The largest n_seg accepted anywhere: keeps every node, DOF and sparse-matrix index well
// inside int. Smaller meshes can still be refused by check_mesh_fits_in_memory.
constexpr int kMaxSegments = 4096;

// The range of a scene value: finite, and between lo and hi (each bound open or closed).
struct ValueBounds {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  bool integer = false;

  bool contains(double v) const;
  std::string requirement() const;  // "must be a finite number > 0", "must be in [0, 0.5)", ...
  std::string range() const;        // "> 0", "[0, 0.5)", "1 to 4096"; "" when only finite
};

// A value's bounds under its scene key, "section.key": the Number and Integer rows of the
// scene field table (scene/scene_fields.h), E and nu too, which the scene keeps as mu and
// lambda. find_scene_problem checks every kept one; the scene file reader checks each
// value as it reads it, and docs/scene-keys.md prints the ranges.
struct BoundedValue {
  std::string key;
  ValueBounds bounds;
};
std::vector<BoundedValue> scene_value_bounds();
const ValueBounds* find_value_bounds(std::string_view key);  // nullptr when none

// The rule of needs_new_mesh (simulation.h), from the scene field table
// (scene/scene_fields.h): a field marked new_mesh differs, or the bodies' count, or a
// body's field marked new_mesh (a body's own material is not), or the tractions.
bool fields_need_new_mesh(const SceneDef& old, const SceneDef& next);

// What is wrong with a scene: the key whose value is out of range or whose relation to
// another fails, why, and the other keys the check read (so that a reader of scene files
// can blame the key the user actually wrote).
struct SceneProblem {
  std::string key;
  std::string reason;
  std::vector<std::string> causes;
};

// Checks every value's range and the initial state (no degenerate or, for a model that
// needs det F > 0, inverted triangle; no node on or through a plane).
std::optional<SceneProblem> find_scene_problem(const SceneDef& scene);
// "" when valid, otherwise "key: reason" naming the offending scene key.
std::string validate_scene(const SceneDef& scene);

}  // namespace invfree
