#include "scene/scene_fields.h"

#include <cmath>
#include <iterator>
#include <type_traits>
#include <utility>

#include "material/models.h"

namespace invfree {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr ValueBounds kFinite{};
constexpr ValueBounds kPositive{0.0, kInf, true, false, false};
constexpr ValueBounds kNonNegative{0.0, kInf, false, false, false};
constexpr ValueBounds kBelowHalf{0.0, 0.5, false, true, false};  // [0, 0.5)
constexpr ValueBounds kSegments{1.0, double(kMaxSegments), false, false, true};
constexpr ValueBounds kCount{0.0, kInf, false, false, true};
constexpr ValueBounds kNewtonIterations{1.0, 100000.0, false, false, true};
constexpr ValueBounds kRampSteps{1.0, 1e9, false, false, true};
constexpr ValueBounds kPolynomialOrder{1.0, 3.0, false, false, true};
constexpr ValueBounds kModes{1.0, 1e6, false, false, true};

// As docs/scene-keys.md writes each type.
constexpr EnumName<FieldType> kFieldTypeNames[] = {
    {FieldType::Number, "number"},        {FieldType::Integer, "integer"},
    {FieldType::Boolean, "boolean"},      {FieldType::Choice, "string"},
    {FieldType::Vector, "[x, y]"},        {FieldType::Text, "path"},
    {FieldType::Points, "[[x, y], ...]"}, {FieldType::Loops, "[[[x, y], ...], ...]"},
    {FieldType::Pairs, "[[i, j], ...]"}};

// core/linalg/linear_solver_kind.h spells its kinds itself (linalg/ is below scene/); the
// pairs are built from that spelling.
const EnumName<LinearSolverKind> kLinearSolverNames[] = {
    {LinearSolverKind::Auto, linear_solver_name(LinearSolverKind::Auto)},
    {LinearSolverKind::Ldlt, linear_solver_name(LinearSolverKind::Ldlt)},
    {LinearSolverKind::Cholmod, linear_solver_name(LinearSolverKind::Cholmod)},
    {LinearSolverKind::Pcg, linear_solver_name(LinearSolverKind::Pcg)},
};

// ---- a SceneDef member as a FieldValue ------------------------------------------------

template <auto F>
using MemberType = std::remove_cvref_t<decltype(std::declval<SceneDef&>().*F)>;

template <auto F>
FieldValue get_member(const SceneDef& s) {
  using T = MemberType<F>;
  if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, double> || std::is_same_v<T, Vec2> ||
                std::is_same_v<T, std::vector<Loop>> || std::is_same_v<T, IndexPairs>)
    return s.*F;
  else if constexpr (std::is_unsigned_v<T>)
    return static_cast<unsigned long long>(s.*F);
  else
    return static_cast<long long>(s.*F);
}

template <auto F>
std::string set_member(SceneDef& s, const FieldValue& v) {
  using T = MemberType<F>;
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    const long long i = std::get<long long>(v);
    if (!std::in_range<T>(i)) return "out of range";
    s.*F = static_cast<T>(i);
  } else {
    s.*F = std::get<T>(v);
  }
  return "";
}

template <auto F, auto& names>
FieldValue get_choice(const SceneDef& s) {  // a value with no name (a mix of corners): the first
  return std::string(enum_name(names, s.*F, names[0].name));
}

template <auto F, auto& names>
std::string set_choice(SceneDef& s, const FieldValue& v) {
  const auto e = enum_from_name(names, std::get<std::string>(v));
  if (!e) return "unknown value";
  s.*F = *e;
  return "";
}

template <auto& names>
const char* choice_at(std::size_t i) {
  return i < std::size(names) ? names[i].name : nullptr;
}

double youngs_modulus(const SceneDef& s) {
  double E = 0.0, nu = 0.0;
  young_poisson_from_lame(s.lame, &E, &nu);
  return E;
}

double poisson_ratio(const SceneDef& s) {
  double E = 0.0, nu = 0.0;
  young_poisson_from_lame(s.lame, &E, &nu);
  return nu;
}

// ---- row builders ---------------------------------------------------------------------

template <double SceneDef::*F>
constexpr SceneField number(const char* section, const char* key, const char* unit,
                            ValueBounds bounds, const char* doc) {
  return {section, key, FieldType::Number, unit,         doc, bounds,
          false,   {},  get_member<F>,     set_member<F>};
}

template <auto F>
constexpr SceneField integer(const char* section, const char* key, ValueBounds bounds,
                             const char* doc) {
  return {section, key, FieldType::Integer, "",           doc, bounds,
          false,   {},  get_member<F>,      set_member<F>};
}

template <bool SceneDef::*F>
constexpr SceneField boolean(const char* section, const char* key, const char* doc) {
  return {section, key, FieldType::Boolean, "",           doc, kFinite,
          false,   {},  get_member<F>,      set_member<F>};
}

template <Vec2 SceneDef::*F>
constexpr SceneField vector(const char* section, const char* key, const char* unit,
                            const char* doc) {
  return {section, key, FieldType::Vector, unit,         doc, kFinite,
          false,   {},  get_member<F>,     set_member<F>};
}

template <auto F, auto& names>
constexpr SceneField choice(const char* section, const char* key, const char* doc) {
  return {section,
          key,
          FieldType::Choice,
          "",
          doc,
          kFinite,
          false,
          {},
          get_choice<F, names>,
          set_choice<F, names>,
          nullptr,
          choice_at<names>};
}

template <std::optional<double> MaterialInput::*In>
constexpr SceneField material(const char* key, const char* unit, ValueBounds bounds,
                              FieldValue (*get)(const SceneDef&), bool kept, const char* doc) {
  return {"material", key, FieldType::Number, unit, doc,     bounds, false,
          {},         get, nullptr,           In,   nullptr, kept};
}

// ---- a member of the scene's [mesh] shape (ShapeDef) -----------------------------------

constexpr ValueBounds kShapeLength{0.0, kInf, true, false, false};  // > 0

template <auto F>
FieldValue get_shape(const SceneDef& s) {
  return FieldValue(s.shape.*F);
}

template <auto F>
std::string set_shape(SceneDef& s, const FieldValue& v) {
  using T = std::remove_cvref_t<decltype(s.shape.*F)>;
  s.shape.*F = std::get<T>(v);
  return "";
}

template <auto F>
constexpr SceneField shape_field(const char* key, FieldType type, const char* unit,
                                 ValueBounds bounds, const char* doc) {
  return {"mesh", key, type, unit, doc, bounds, true, {}, get_shape<F>, set_shape<F>};
}

FieldValue get_shape_kind(const SceneDef& s) {
  return std::string(shape_kind_name(s.shape.kind));
}

std::string set_shape_kind(SceneDef& s, const FieldValue& v) {
  const auto k = shape_kind_from_name(std::get<std::string>(v));
  if (!k) return "unknown value";
  s.shape.kind = *k;
  return "";
}

// Changing the field needs a new mesh, masses or unknowns (needs_new_mesh).
constexpr SceneField rebuilds(SceneField f) {
  f.new_mesh = true;
  return f;
}

constexpr SceneField with_slider(SceneField f, SliderRange r) {
  f.slider = r;
  return f;
}

// ---- the tables -----------------------------------------------------------------------

constexpr SceneSection kSections[] = {
    {"mesh", nullptr, "the body's shape and its triangle mesh"},
    {"material", nullptr, "the elastic material: `E` and `nu`, or `mu` and `lambda`"},
    {"time", nullptr, "the time step and Newton's stopping rule"},
    {"solver", nullptr, "how each step's incremental potential is minimised"},
    {"initial", nullptr, "the initial state"},
    {"gravity", &SceneDef::has_gravity, "gravity; no section, no gravity"},
    {"ground", &SceneDef::has_ground,
     "the ground plane (IPC barrier, lagged friction); no section, no ground"},
    {"ceiling", &SceneDef::has_ceiling,
     "a plane moving down until it stops, squashing the square; no section, no ceiling"},
    {"barrier", nullptr, "the IPC log barrier of both planes"},
    {"mass_spring", &SceneDef::has_mass_spring,
     "springs on the mesh's edges and both diagonals of every cell, or on the node pairs "
     "listed, instead of the material's triangles (the course's chapters 0-5); no section, "
     "no springs"},
    {"fixed", &SceneDef::has_fixed,
     "nodes held at their initial positions, chosen in rest space; no section, none"},
    {"self_contact", &SceneDef::has_self_contact,
     "IPC contact of the boundary with itself (docs/method.md); on by default, also with no "
     "section, except with [mass_spring] or [fixed] (there `enabled = true` is refused) and "
     "symplectic Euler (there only its intersection check would run)"},
    {"modes", nullptr, "`invfree modes`: the linear modal analysis of the scene (docs/modes.md)"},
    {"reduced", nullptr,
     "Newton's steps in a subspace x = x0 + B q (the course's chapter 9, "
     "core/scene/reduced_basis.h)"},
};

// Slider ranges (app/live/param_limits.h), each narrower than the valid range on purpose:
//  - mu, lambda: the upper ends are where the `compress` demo's penalty ceiling still makes
//    progress (much stiffer squares hit Newton's iteration cap under it: the run pauses
//    with a banner); mu's lower end keeps the log slider finite.
//  - nu: stops short of the incompressible limit 0.5, where lambda is infinite.
//  - h, tol: the decades a class explores at interactive speed.
//  - ground friction: 0 (ice) to 2 (rubber on rubber is about 1).
//  - ceiling velocity: downwards only (the panel's "ceiling speed" is its negative), at
//    most 5 m/s.
//  - spring stiffness k: the decades around the default 1e5 N/m.
constexpr SceneField kFields[] = {
    rebuilds(number<&SceneDef::side>("mesh", "side", "m", kPositive, "edge length of the square")),
    rebuilds(integer<&SceneDef::n_seg>("mesh", "n_seg", kSegments,
                                       "segments per side (2 n_seg^2 triangles)")),
    rebuilds(
        number<&SceneDef::density>("mesh", "density", "kg/m^2", kPositive, "mass per unit area")),
    rebuilds(choice<&SceneDef::mass, kMassModeNames>(
        "mesh", "mass",
        "node masses: total / node count (the demo's), or a third of each triangle's to its "
        "nodes")),
    rebuilds(number<&SceneDef::node_mass>(
        "mesh", "node_mass", "kg", kNonNegative,
        "every node's mass when > 0 (the course's chapter 0 particles), instead of density")),
    rebuilds(
        number<&SceneDef::jitter>("mesh", "jitter", "", kBelowHalf,
                                  "random initial node offset, as a fraction of the edge length")),
    rebuilds(integer<&SceneDef::seed>("mesh", "seed", kCount,
                                      "the jitter's pseudo-random seed (SplitMix64)")),
    {"mesh",
     "shape",
     FieldType::Choice,
     "",
     "the body's shape: the side x n_seg grid, or an outline meshed by CGAL (docs/shapes.md)",
     kFinite,
     true,
     {},
     get_shape_kind,
     set_shape_kind,
     nullptr,
     choice_at<kShapeKindNames>},
    shape_field<&ShapeDef::width>("width", FieldType::Number, "m", kShapeLength,
                                  "rectangle: its width"),
    shape_field<&ShapeDef::height>("height", FieldType::Number, "m", kShapeLength,
                                   "rectangle: its height"),
    shape_field<&ShapeDef::radius>("radius", FieldType::Number, "m", kShapeLength,
                                   "disk, ring: the outer radius"),
    shape_field<&ShapeDef::inner_radius>("inner_radius", FieldType::Number, "m", kShapeLength,
                                         "ring: the hole's radius (< radius)"),
    shape_field<&ShapeDef::outline>("outline", FieldType::Points, "m", kFinite,
                                    "polygon: its corners, either orientation"),
    shape_field<&ShapeDef::holes>("holes", FieldType::Loops, "m", kFinite,
                                  "polygon: holes, each a list of corners inside the outline"),
    shape_field<&ShapeDef::points>("points", FieldType::Points, "m", kFinite,
                                   "points: the particles' rest positions (nodes, no triangles)"),
    shape_field<&ShapeDef::file>("file", FieldType::Text, "", kFinite,
                                 "svg, mesh: the file, relative to the scene file"),
    shape_field<&ShapeDef::path_id>("path_id", FieldType::Text, "", kFinite,
                                    "svg: the id of the one path to use (\"\": every closed path)"),
    shape_field<&ShapeDef::scale>("scale", FieldType::Number, "m", kShapeLength,
                                  "svg: metres per SVG user unit"),
    shape_field<&ShapeDef::max_edge>("max_edge", FieldType::Number, "m", kNonNegative,
                                     "target edge length of a meshed shape (0: the longer side "
                                     "of its bounding box / n_seg)"),
    choice<&SceneDef::model, kModelNames>("material", "model", "the elastic energy density"),
    material<&MaterialInput::E>(
        "E", "Pa", kPositive, [](const SceneDef& s) { return FieldValue(youngs_modulus(s)); },
        false, "Young's modulus (kept as mu and lambda)"),
    with_slider(
        material<&MaterialInput::nu>(
            "nu", "", kBelowHalf, [](const SceneDef& s) { return FieldValue(poisson_ratio(s)); },
            false, "Poisson's ratio (kept as mu and lambda)"),
        {0.0, 0.499}),
    with_slider(material<&MaterialInput::mu>(
                    "mu", "Pa", kPositive, [](const SceneDef& s) { return FieldValue(s.lame.mu); },
                    true, "Lame's mu (shear modulus), instead of E and nu"),
                {1e2, 1e7}),
    with_slider(material<&MaterialInput::lambda>(
                    "lambda", "Pa", kNonNegative,
                    [](const SceneDef& s) { return FieldValue(s.lame.lambda); }, true,
                    "Lame's lambda, instead of E and nu"),
                {0.0, 1e8}),
    with_slider(number<&SceneDef::h>("time", "h", "s", kPositive, "time step"), {1e-4, 0.05}),
    with_slider(
        number<&SceneDef::tol>("time", "tol", "m/s", kPositive, "Newton stops when ‖p‖∞ / h < tol"),
        {1e-5, 1.0}),
    integer<&SceneDef::max_newton>("time", "max_newton", kNewtonIterations,
                                   "Newton iterations per step at most"),
    integer<&SceneDef::ramp_steps>("time", "ramp_steps", kRampSteps,
                                   "loads (gravity, tractions) grow linearly over this many steps"),
    choice<&SceneDef::projection, kProjectionNames>(
        "solver", "projection",
        "elastic Hessian made PSD: the lecture's per-part clamp, each triangle's 6x6 "
        "eigenvalues clamped, or none"),
    boolean<&SceneDef::inversion_filter>("solver", "inversion_filter",
                                         "the line search never lets a triangle invert"),
    boolean<&SceneDef::step_expansion>("solver", "step_expansion",
                                       "Newton's safeguard: grow a step that beats its model"),
    boolean<&SceneDef::friction_crossing_stop>(
        "solver", "friction_crossing_stop",
        "Newton's safeguard: a sliding node stops where its slip changes sign"),
    choice<&SceneDef::integrator, kIntegratorNames>(
        "solver", "integrator",
        "time integration, or \"static\": each step the equilibrium under its loads"),
    choice<&SceneDef::linear_solver, kLinearSolverNames>(
        "solver", "linear_solver",
        "solver of Newton's linear system (core/linalg/linear_solver_kind.h)"),
    vector<&SceneDef::initial_velocity>("initial", "velocity", "m/s",
                                        "velocity of every node at t = 0"),
    boolean<&SceneDef::has_gravity>("gravity", "enabled", "false switches gravity off"),
    vector<&SceneDef::gravity>("gravity", "g", "m/s^2", "gravitational acceleration"),
    boolean<&SceneDef::gravity_per_spring>(
        "gravity", "per_spring",
        "the course's chapter 0 quirk: a node's gravity counted once per spring it ends"),
    boolean<&SceneDef::has_ground>("ground", "enabled", "false switches the ground off"),
    number<&SceneDef::ground_y>("ground", "y", "m", kFinite, "height of the ground"),
    with_slider(
        number<&SceneDef::friction>("ground", "friction", "", kNonNegative, "friction coefficient"),
        {0.0, 2.0}),
    rebuilds(
        boolean<&SceneDef::has_ceiling>("ceiling", "enabled", "false switches the ceiling off")),
    number<&SceneDef::ceiling_y>("ceiling", "y", "m", kFinite, "height of the ceiling at t = 0"),
    with_slider(number<&SceneDef::ceiling_velocity>("ceiling", "velocity", "m/s", kFinite,
                                                    "vertical velocity of the ceiling"),
                {-5.0, 0.0}),
    number<&SceneDef::ceiling_stop>("ceiling", "stop", "m", kFinite,
                                    "it stops once its start-of-step height is at or below this"),
    number<&SceneDef::dhat>("barrier", "dhat", "m", kPositive,
                            "distance below which the barrier acts"),
    number<&SceneDef::kappa>("barrier", "kappa", "Pa", kPositive, "barrier stiffness"),
    vector<&SceneDef::initial_stretch>(
        "initial", "stretch", "", "rest positions scaled by [sx, sy] about the origin at t = 0"),
    vector<&SceneDef::ground_normal>("ground", "normal", "",
                                     "the ground's normal (any slope); the plane passes through "
                                     "(0, y)"),
    rebuilds(boolean<&SceneDef::has_mass_spring>("mass_spring", "enabled",
                                                 "false switches the springs off (the material's "
                                                 "triangles instead)")),
    with_slider(
        number<&SceneDef::spring_stiffness>("mass_spring", "stiffness", "N/m", kPositive,
                                            "k of every spring: 1/2 k l^2 (|d|^2 / l^2 - 1)^2"),
        {1e1, 1e8}),
    choice<&SceneDef::spring_law, kSpringLawNames>(
        "mass_spring", "law",
        "the spring's energy: green 1/2 k l^2 (|d|^2 / l^2 - 1)^2, hooke 1/2 k (|d| - l)^2"),
    {"mass_spring",
     "springs",
     FieldType::Pairs,
     "",
     "node index pairs, rest lengths from the rest positions ([]: the mesh's edges and both "
     "diagonals)",
     kFinite,
     true,
     {},
     get_member<&SceneDef::springs>,
     set_member<&SceneDef::springs>},
    rebuilds(boolean<&SceneDef::has_fixed>("fixed", "enabled", "false frees every node")),
    rebuilds(choice<&SceneDef::fixed_corners, kFixedCornersNames>(
        "fixed", "corners",
        "corners of the rest mesh's bounding box held fixed (\"top\": top-left and top-right)")),
    rebuilds(vector<&SceneDef::fixed_box_min>("fixed", "box_min", "m",
                                              "nodes whose rest position is in [box_min, box_max] "
                                              "are held fixed (min > max: no box)")),
    rebuilds(vector<&SceneDef::fixed_box_max>("fixed", "box_max", "m", "the box's upper corner")),
    rebuilds(choice<&SceneDef::fixed_components, kFixedComponentsNames>(
        "fixed", "components",
        "the fixed nodes' held coordinates: both, or only x or y (a roller support)")),
    {"fixed",
     "boxes",
     FieldType::Loops,
     "m",
     "more boxes, each [[x_min, y_min], [x_max, y_max]]: their nodes are held fixed too",
     kFinite,
     true,
     {},
     get_member<&SceneDef::fixed_boxes>,
     set_member<&SceneDef::fixed_boxes>},
    {"fixed",
     "x_boxes",
     FieldType::Loops,
     "m",
     "rollers: boxes like `boxes` whose nodes are held in x only (free to slide in y)",
     kFinite,
     true,
     {},
     get_member<&SceneDef::fixed_x_boxes>,
     set_member<&SceneDef::fixed_x_boxes>},
    {"fixed",
     "y_boxes",
     FieldType::Loops,
     "m",
     "rollers: boxes like `boxes` whose nodes are held in y only (free to slide in x)",
     kFinite,
     true,
     {},
     get_member<&SceneDef::fixed_y_boxes>,
     set_member<&SceneDef::fixed_y_boxes>},
    boolean<&SceneDef::has_self_contact>("self_contact", "enabled",
                                         "false switches self-contact off"),
    number<&SceneDef::self_friction>("self_contact", "friction", "", kNonNegative,
                                     "friction coefficient between boundary node and edge"),
    boolean<&SceneDef::self_contact_ccd>(
        "self_contact", "ccd",
        "the line search's CCD filter (false only to show what goes wrong without it)"),
    choice<&SceneDef::modes_element, kModalElementNames>(
        "modes", "element",
        "invfree modes' elements: linear triangles on the mesh, or bilinear quads (2x2 Gauss) "
        "from its triangle pairs (a structured grid)"),
    rebuilds(choice<&SceneDef::reduced_basis, kReducedBasisNames>(
        "reduced", "basis",
        "the subspace: every unknown, polynomials of the rest position, or the rest "
        "Hessian's lowest eigenvectors")),
    rebuilds(integer<&SceneDef::reduced_order>(
        "reduced", "order", kPolynomialOrder,
        "the polynomial basis's degree: 1 affine, 2 quadratic, 3 cubic")),
    rebuilds(integer<&SceneDef::reduced_modes>(
        "reduced", "modes", kModes,
        "the modal basis's eigenvectors, rigid modes included (a cut inside a degenerate "
        "group is refused)")),
};

// ---- [[body]] -------------------------------------------------------------------------

template <auto F>
std::optional<FieldValue> get_body(const BodyDef& b) {
  using T = std::remove_cvref_t<decltype(b.*F)>;
  if constexpr (std::is_same_v<T, Vec2>) {
    return FieldValue(b.*F);
  } else {
    if (!(b.*F)) return std::nullopt;
    if constexpr (std::is_same_v<T, std::optional<int>>)
      return FieldValue(static_cast<long long>(*(b.*F)));
    else if constexpr (std::is_same_v<T, std::optional<ShapeKind>>)
      return FieldValue(std::string(shape_kind_name(*(b.*F))));
    else
      return FieldValue(*(b.*F));
  }
}

template <auto F>
void set_body(BodyDef& b, const FieldValue& v) {
  using T = std::remove_cvref_t<decltype(b.*F)>;
  if constexpr (std::is_same_v<T, Vec2>)
    b.*F = std::get<Vec2>(v);
  else if constexpr (std::is_same_v<T, std::optional<int>>)
    b.*F = static_cast<int>(std::get<long long>(v));
  else if constexpr (std::is_same_v<T, std::optional<ShapeKind>>)
    b.*F = shape_kind_from_name(std::get<std::string>(v));  // the reader checked the name
  else
    b.*F = std::get<typename T::value_type>(v);
}

std::optional<FieldValue> body_mu(const BodyDef& b) {
  if (!b.lame) return std::nullopt;
  return FieldValue(b.lame->mu);
}

std::optional<FieldValue> body_lambda(const BodyDef& b) {
  if (!b.lame) return std::nullopt;
  return FieldValue(b.lame->lambda);
}

constexpr BodyField kBodyFields[] = {
    {"side", FieldType::Number, "m", "edge length of this body's square (default: mesh.side)",
     "mesh.side", true, get_body<&BodyDef::side>, set_body<&BodyDef::side>},
    {"n_seg", FieldType::Integer, "", "segments per side (default: mesh.n_seg)", "mesh.n_seg", true,
     get_body<&BodyDef::n_seg>, set_body<&BodyDef::n_seg>},
    {"shape", FieldType::Choice, "", "its shape (default: mesh.shape)", nullptr, true,
     get_body<&BodyDef::shape>, set_body<&BodyDef::shape>, nullptr, choice_at<kShapeKindNames>},
    {"width", FieldType::Number, "m", "rectangle: its width (default: mesh.width)", "mesh.width",
     true, get_body<&BodyDef::width>, set_body<&BodyDef::width>},
    {"height", FieldType::Number, "m", "rectangle: its height (default: mesh.height)",
     "mesh.height", true, get_body<&BodyDef::height>, set_body<&BodyDef::height>},
    {"radius", FieldType::Number, "m", "disk, ring: outer radius (default: mesh.radius)",
     "mesh.radius", true, get_body<&BodyDef::radius>, set_body<&BodyDef::radius>},
    {"inner_radius", FieldType::Number, "m", "ring: the hole's radius (default: mesh.inner_radius)",
     "mesh.inner_radius", true, get_body<&BodyDef::inner_radius>, set_body<&BodyDef::inner_radius>},
    {"outline", FieldType::Points, "m", "polygon: its corners (default: mesh.outline)", nullptr,
     true, get_body<&BodyDef::outline>, set_body<&BodyDef::outline>},
    {"holes", FieldType::Loops, "m", "polygon: its holes (default: mesh.holes)", nullptr, true,
     get_body<&BodyDef::holes>, set_body<&BodyDef::holes>},
    {"file", FieldType::Text, "", "svg, mesh: its file, relative to the scene file", nullptr, true,
     get_body<&BodyDef::file>, set_body<&BodyDef::file>},
    {"path_id", FieldType::Text, "", "svg: the id of the one path to use", nullptr, true,
     get_body<&BodyDef::path_id>, set_body<&BodyDef::path_id>},
    {"scale", FieldType::Number, "m", "svg: metres per SVG user unit (default: mesh.scale)",
     "mesh.scale", true, get_body<&BodyDef::scale>, set_body<&BodyDef::scale>},
    {"max_edge", FieldType::Number, "m", "target edge length (default: mesh.max_edge)",
     "mesh.max_edge", true, get_body<&BodyDef::max_edge>, set_body<&BodyDef::max_edge>},
    {"offset", FieldType::Vector, "m", "where its own frame (a square's centre) sits at rest",
     nullptr, true, get_body<&BodyDef::offset>, set_body<&BodyDef::offset>},
    {"velocity", FieldType::Vector, "m/s", "its velocity at t = 0 (default: initial.velocity)",
     nullptr, true, get_body<&BodyDef::velocity>, set_body<&BodyDef::velocity>},
    {"E", FieldType::Number, "Pa", "its own Young's modulus (default: [material])", "material.E",
     false, nullptr, nullptr, &MaterialInput::E},
    {"nu", FieldType::Number, "", "its own Poisson's ratio", "material.nu", false, nullptr, nullptr,
     &MaterialInput::nu},
    {"mu", FieldType::Number, "Pa", "its own Lame mu, instead of E and nu", "material.mu", false,
     body_mu, nullptr, &MaterialInput::mu},
    {"lambda", FieldType::Number, "Pa", "its own Lame lambda, instead of E and nu",
     "material.lambda", false, body_lambda, nullptr, &MaterialInput::lambda},
};

bool has_bounds(const SceneField& f) {
  return f.type == FieldType::Number || f.type == FieldType::Integer;
}

}  // namespace

const char* field_type_name(FieldType type) {
  return enum_name(kFieldTypeNames, type);
}

double field_number(const FieldValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* i = std::get_if<long long>(&v)) return static_cast<double>(*i);
  if (const auto* u = std::get_if<unsigned long long>(&v)) return static_cast<double>(*u);
  return std::numeric_limits<double>::quiet_NaN();
}

std::vector<std::string> SceneField::choices() const {
  std::vector<std::string> out;
  if (choice)
    for (std::size_t i = 0; choice(i); ++i) out.emplace_back(choice(i));
  return out;
}

std::span<const SceneField> scene_fields() {
  return kFields;
}

std::span<const SceneSection> scene_sections() {
  return kSections;
}

const SceneField* find_scene_field(std::string_view section, std::string_view key) {
  for (const auto& f : kFields)
    if (section == f.section && key == f.key) return &f;
  return nullptr;
}

const SceneField* find_scene_field(std::string_view name) {
  const size_t dot = name.find('.');
  if (dot == std::string_view::npos) return nullptr;
  return find_scene_field(name.substr(0, dot), name.substr(dot + 1));
}

const SceneSection* find_scene_section(std::string_view name) {
  for (const auto& s : kSections)
    if (name == s.name) return &s;
  return nullptr;
}

std::vector<BoundedValue> scene_value_bounds() {
  std::vector<BoundedValue> out;
  for (const auto& f : kFields)
    if (has_bounds(f)) out.push_back({f.name(), f.bounds});
  return out;
}

const ValueBounds* find_value_bounds(std::string_view key) {
  const SceneField* f = find_scene_field(key);
  return f && has_bounds(*f) ? &f->bounds : nullptr;
}

std::string assign_field(const SceneField& f, SceneDef& s, MaterialInput& material,
                         const FieldValue& v) {
  if (has_bounds(f) && !f.bounds.contains(field_number(v))) return f.bounds.requirement();
  if (f.input) {
    material.*(f.input) = field_number(v);
    return "";
  }
  return f.set(s, v);
}

std::string apply_material(SceneDef& s, const MaterialInput& in) {
  if ((in.E || in.nu) && (in.mu || in.lambda))
    return std::string(in.E ? "material.E" : "material.nu") +
           ": give either E and nu or mu and lambda, not both";
  if (in.E || in.nu) {
    const std::string key = in.E ? "material.E" : "material.nu";
    s.lame =
        lame_from_young_poisson(in.E.value_or(youngs_modulus(s)), in.nu.value_or(poisson_ratio(s)));
    if (!std::isfinite(s.lame.mu) || !std::isfinite(s.lame.lambda))
      return key + ": too large (mu and lambda must be finite)";
    if (!(s.lame.mu > 0.0)) return key + ": too small (mu = E / (2 (1 + nu)) underflows to 0)";
  } else {
    if (in.mu) s.lame.mu = *in.mu;
    if (in.lambda) s.lame.lambda = *in.lambda;
  }
  return "";
}

std::vector<std::string> BodyField::choices() const {
  std::vector<std::string> out;
  if (choice)
    for (std::size_t i = 0; choice(i); ++i) out.emplace_back(choice(i));
  return out;
}

std::span<const BodyField> body_fields() {
  return kBodyFields;
}

const BodyField* find_body_field(std::string_view key) {
  for (const auto& f : kBodyFields)
    if (key == f.key) return &f;
  return nullptr;
}

bool fields_need_new_mesh(const SceneDef& old, const SceneDef& next) {
  for (const auto& f : kFields)
    if (f.new_mesh && f.get(old) != f.get(next)) return true;
  if (old.bodies.size() != next.bodies.size()) return true;
  // The tractions' nodal forces and pressure edges are found once per simulation.
  if (old.tractions != next.tractions) return true;
  for (size_t k = 0; k < old.bodies.size(); ++k)
    for (const auto& f : kBodyFields)
      if (f.new_mesh && f.get(old.bodies[k]) != f.get(next.bodies[k])) return true;
  return false;
}

}  // namespace invfree
