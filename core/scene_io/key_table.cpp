#include "scene_io/key_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <type_traits>
#include <utility>

#include "scene_io/error_text.h"
#include "scene_io/scene_keys.h"

namespace invfree::scene_io {

std::string toml_type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date/time";
  }
}

std::string read_number(const toml::node& n, double& out) {
  if (auto v = n.value<double>(); v && (n.is_integer() || n.is_floating_point())) {
    out = *v;
    if (!std::isfinite(out)) return "must be a finite number";
    return "";
  }
  return "expected a number, got " + toml_type_name(n);
}

std::string bounds_problem(std::string_view key, double v) {
  const ValueBounds* b = find_value_bounds(key);
  return b && !b->contains(v) ? b->requirement() : "";
}

namespace {

// ---- typed readers: return "" or a reason -------------------------------------------

std::string read_int(const toml::node& n, long long& out) {
  if (n.is_integer()) {
    out = n.as_integer()->get();
    return "";
  }
  if (n.is_floating_point()) {
    const double d = n.as_floating_point()->get();
    if (std::isfinite(d) && d == std::floor(d) && std::abs(d) < 1e15) {
      out = static_cast<long long>(d);
      return "";
    }
  }
  return "expected an integer, got " + toml_type_name(n);
}

std::string read_bool(const toml::node& n, bool& out) {
  if (!n.is_boolean()) return "expected true or false, got " + toml_type_name(n);
  out = n.as_boolean()->get();
  return "";
}

std::string read_vec2(const toml::node& n, Vec2& out) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2) return "expected an array of two numbers, e.g. [0.0, -9.81]";
  for (int k = 0; k < 2; ++k)
    if (auto r = read_number(*a->get(k), out[k]); !r.empty())
      return "element " + std::to_string(k) + ": " + r;
  return "";
}

// The range the core gives the key (scene_value_bounds); "" when v is within it.
std::string check_bounds(const KeySpec& k, double v) {
  return bounds_problem(k.name(), v);
}

// ---- readers and writers of each value type, bound to a SceneDef field ----------------

template <double SceneDef::*F>
std::string read_number_field(const KeySpec& k, SceneDef& s, MaterialInput&, const toml::node& n) {
  double v = 0.0;
  if (auto r = read_number(n, v); !r.empty()) return r;
  if (auto r = check_bounds(k, v); !r.empty()) return r;
  s.*F = v;
  return "";
}

template <double SceneDef::*F>
std::string write_number_field(const SceneDef& s) {
  return toml_number(s.*F);
}

template <auto F>  // an integer field
std::string read_integer_field(const KeySpec& k, SceneDef& s, MaterialInput&, const toml::node& n) {
  using T = std::remove_reference_t<decltype(std::declval<SceneDef&>().*F)>;
  long long v = 0;
  if (auto r = read_int(n, v); !r.empty()) return r;
  if (auto r = check_bounds(k, static_cast<double>(v)); !r.empty()) return r;
  if (!std::in_range<T>(v)) return "out of range";
  s.*F = static_cast<T>(v);
  return "";
}

template <auto F>
std::string write_integer_field(const SceneDef& s) {
  return std::to_string(s.*F);
}

template <bool SceneDef::*F>
std::string read_bool_field(const KeySpec&, SceneDef& s, MaterialInput&, const toml::node& n) {
  return read_bool(n, s.*F);
}

template <bool SceneDef::*F>
std::string write_bool_field(const SceneDef& s) {
  return s.*F ? "true" : "false";
}

template <Vec2 SceneDef::*F>
std::string read_vec2_field(const KeySpec&, SceneDef& s, MaterialInput&, const toml::node& n) {
  return read_vec2(n, s.*F);
}

template <Vec2 SceneDef::*F>
std::string write_vec2_field(const SceneDef& s) {
  std::string out(1, '[');
  out += toml_number((s.*F).x());
  out += ", ";
  out += toml_number((s.*F).y());
  out += ']';
  return out;
}

std::string choice_list(const KeySpec& k) {
  std::string out;
  for (const char* c : k.choices) out += std::string(out.empty() ? "\"" : ", \"") + c + "\"";
  return out;
}

// An enum field spelt as a string: `parse` from the scene-file spelling, `name` back.
template <auto F, auto parse>
std::string read_choice_field(const KeySpec& k, SceneDef& s, MaterialInput&, const toml::node& n) {
  if (!n.is_string()) return "expected a string, got " + toml_type_name(n);
  const std::string text = n.as_string()->get();
  const auto v = parse(text);
  if (!v)  // invfree:: so that libc++'s std::quoted (found by ADL) is not taken
    return "unknown value " + invfree::quoted(text) + " (expected one of " + choice_list(k) + ")";
  s.*F = *v;
  return "";
}

template <auto F, auto name>
std::string write_choice_field(const SceneDef& s) {
  std::string out(1, '"');  // (not "\"" + ...: GCC 12 warns falsely on that form)
  out += name(s.*F);
  out += '"';
  return out;
}

template <std::optional<double> MaterialInput::*F>
std::string read_material(const KeySpec& k, SceneDef&, MaterialInput& m, const toml::node& n) {
  double v = 0.0;
  if (auto r = read_number(n, v); !r.empty()) return r;
  if (auto r = check_bounds(k, v); !r.empty()) return r;
  m.*F = v;
  return "";
}

const char* mass_name(MassMode m) {
  return m == MassMode::Uniform ? "uniform" : "lumped";
}

std::optional<MassMode> mass_from_name(std::string_view s) {
  if (s == "uniform") return MassMode::Uniform;
  if (s == "lumped") return MassMode::Lumped;
  return std::nullopt;
}

// ---- row builders ---------------------------------------------------------------------

template <double SceneDef::*F>
constexpr KeySpec number(const char* section, const char* key, const char* unit, const char* doc) {
  return {section, key, ValueType::Number,    unit,
          doc,     {},  read_number_field<F>, write_number_field<F>};
}

template <auto F>
constexpr KeySpec integer(const char* section, const char* key, const char* doc) {
  return {section, key, ValueType::Integer,    "",
          doc,     {},  read_integer_field<F>, write_integer_field<F>};
}

template <bool SceneDef::*F>
constexpr KeySpec boolean(const char* section, const char* key, const char* doc) {
  return {section, key, ValueType::Boolean, "", doc, {}, read_bool_field<F>, write_bool_field<F>};
}

template <Vec2 SceneDef::*F>
constexpr KeySpec vector(const char* section, const char* key, const char* unit, const char* doc) {
  return {section, key, ValueType::Vector, unit, doc, {}, read_vec2_field<F>, write_vec2_field<F>};
}

template <auto F, auto parse, auto name>
constexpr KeySpec choice(const char* section, const char* key, std::span<const char* const> choices,
                         const char* doc) {
  return {section, key,     ValueType::Choice,           "",
          doc,     choices, read_choice_field<F, parse>, write_choice_field<F, name>};
}

template <std::optional<double> MaterialInput::*F>
constexpr KeySpec material(const char* key, const char* unit, const char* doc,
                           std::string (*write)(const SceneDef&), bool kept) {
  return {"material", key, ValueType::Number, unit, doc, {}, read_material<F>, write, kept};
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

// ---- the tables -----------------------------------------------------------------------

constexpr SectionSpec kSections[] = {
    {"mesh", nullptr, "the square and its triangle mesh"},
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
     "springs on the mesh's edges and both diagonals of every cell instead of the "
     "material's triangles (the course's chapters 1-5); no section, no springs"},
    {"fixed", &SceneDef::has_fixed,
     "nodes held at their initial positions, chosen in rest space; no section, none"},
    {"self_contact", &SceneDef::has_self_contact,
     "IPC contact of the boundary with itself (docs/method.md); no section, none"},
};

constexpr const char* kMassChoices[] = {"uniform", "lumped"};
constexpr const char* kModelChoices[] = {"neo-hookean", "linear", "arap", "stable-neo-hookean"};
constexpr const char* kProjectionChoices[] = {"diagonal", "full", "none"};
constexpr const char* kIntegratorChoices[] = {"implicit-euler", "symplectic-euler"};
constexpr const char* kLinearSolverChoices[] = {"auto", "ldlt", "cholmod", "pcg"};
constexpr const char* kCornerChoices[] = {"none",         "top-left", "top-right", "bottom-left",
                                          "bottom-right", "top",      "bottom",    "left",
                                          "right",        "all"};

const KeySpec kKeys[] = {
    number<&SceneDef::side>("mesh", "side", "m", "edge length of the square"),
    integer<&SceneDef::n_seg>("mesh", "n_seg", "segments per side (2 n_seg^2 triangles)"),
    number<&SceneDef::density>("mesh", "density", "kg/m^2", "mass per unit area"),
    choice<&SceneDef::mass, mass_from_name, mass_name>(
        "mesh", "mass", kMassChoices,
        "node masses: total / node count (the demo's), or a third of each triangle's to its "
        "nodes"),
    number<&SceneDef::jitter>("mesh", "jitter", "",
                              "random initial node offset, as a fraction of the edge length"),
    integer<&SceneDef::seed>("mesh", "seed", "the jitter's pseudo-random seed (SplitMix64)"),
    choice<&SceneDef::model, model_from_name, model_name>("material", "model", kModelChoices,
                                                          "the elastic energy density"),
    material<&MaterialInput::E>(
        "E", "Pa", "Young's modulus (kept as mu and lambda)",
        [](const SceneDef& s) { return toml_number(youngs_modulus(s)); }, false),
    material<&MaterialInput::nu>(
        "nu", "", "Poisson's ratio (kept as mu and lambda)",
        [](const SceneDef& s) { return toml_number(poisson_ratio(s)); }, false),
    material<&MaterialInput::mu>(
        "mu", "Pa", "Lame's mu (shear modulus), instead of E and nu",
        [](const SceneDef& s) { return toml_number(s.lame.mu); }, true),
    material<&MaterialInput::lambda>(
        "lambda", "Pa", "Lame's lambda, instead of E and nu",
        [](const SceneDef& s) { return toml_number(s.lame.lambda); }, true),
    number<&SceneDef::h>("time", "h", "s", "time step"),
    number<&SceneDef::tol>("time", "tol", "m/s", "Newton stops when ‖p‖∞ / h < tol"),
    integer<&SceneDef::max_newton>("time", "max_newton", "Newton iterations per step at most"),
    choice<&SceneDef::projection, projection_from_name, projection_name>(
        "solver", "projection", kProjectionChoices,
        "elastic Hessian made PSD: the lecture's per-part clamp, each triangle's 6x6 "
        "eigenvalues clamped, or none"),
    boolean<&SceneDef::inversion_filter>("solver", "inversion_filter",
                                         "the line search never lets a triangle invert"),
    boolean<&SceneDef::step_expansion>("solver", "step_expansion",
                                       "Newton's safeguard: grow a step that beats its model"),
    boolean<&SceneDef::friction_crossing_stop>(
        "solver", "friction_crossing_stop",
        "Newton's safeguard: a sliding node stops where its slip changes sign"),
    choice<&SceneDef::integrator, integrator_from_name, integrator_name>(
        "solver", "integrator", kIntegratorChoices, "time integration"),
    choice<&SceneDef::linear_solver, linear_solver_from_name, linear_solver_name>(
        "solver", "linear_solver", kLinearSolverChoices,
        "solver of Newton's linear system (core/linalg/linear_solver_kind.h)"),
    vector<&SceneDef::initial_velocity>("initial", "velocity", "m/s",
                                        "velocity of every node at t = 0"),
    boolean<&SceneDef::has_gravity>("gravity", "enabled", "false switches gravity off"),
    vector<&SceneDef::gravity>("gravity", "g", "m/s^2", "gravitational acceleration"),
    boolean<&SceneDef::has_ground>("ground", "enabled", "false switches the ground off"),
    number<&SceneDef::ground_y>("ground", "y", "m", "height of the ground"),
    number<&SceneDef::friction>("ground", "friction", "", "friction coefficient"),
    boolean<&SceneDef::has_ceiling>("ceiling", "enabled", "false switches the ceiling off"),
    number<&SceneDef::ceiling_y>("ceiling", "y", "m", "height of the ceiling at t = 0"),
    number<&SceneDef::ceiling_velocity>("ceiling", "velocity", "m/s",
                                        "vertical velocity of the ceiling"),
    number<&SceneDef::ceiling_stop>("ceiling", "stop", "m",
                                    "it stops once its start-of-step height is at or below this"),
    number<&SceneDef::dhat>("barrier", "dhat", "m", "distance below which the barrier acts"),
    number<&SceneDef::kappa>("barrier", "kappa", "Pa", "barrier stiffness"),
    vector<&SceneDef::initial_stretch>(
        "initial", "stretch", "", "rest positions scaled by [sx, sy] about the origin at t = 0"),
    vector<&SceneDef::ground_normal>("ground", "normal", "",
                                     "the ground's normal (any slope); the plane passes through "
                                     "(0, y)"),
    boolean<&SceneDef::has_mass_spring>("mass_spring", "enabled",
                                        "false switches the springs off (the material's "
                                        "triangles instead)"),
    number<&SceneDef::spring_stiffness>("mass_spring", "stiffness", "N/m",
                                        "k of every spring: 1/2 k l^2 (|d|^2 / l^2 - 1)^2"),
    boolean<&SceneDef::has_fixed>("fixed", "enabled", "false frees every node"),
    choice<&SceneDef::fixed_corners, fixed_corners_from_name, fixed_corners_name>(
        "fixed", "corners", kCornerChoices,
        "corners of the rest mesh's bounding box held fixed (\"top\": top-left and top-right)"),
    vector<&SceneDef::fixed_box_min>("fixed", "box_min", "m",
                                     "nodes whose rest position is in [box_min, box_max] are "
                                     "held fixed (min > max: no box)"),
    vector<&SceneDef::fixed_box_max>("fixed", "box_max", "m", "the box's upper corner"),
    boolean<&SceneDef::has_self_contact>("self_contact", "enabled",
                                         "false switches self-contact off"),
    number<&SceneDef::self_friction>("self_contact", "friction", "",
                                     "friction coefficient between boundary node and edge"),
    boolean<&SceneDef::self_contact_ccd>(
        "self_contact", "ccd",
        "the line search's CCD filter (false only to show what goes wrong without it)"),
};

}  // namespace

const char* value_type_name(ValueType type) {
  switch (type) {
    case ValueType::Number:
      return "number";
    case ValueType::Integer:
      return "integer";
    case ValueType::Boolean:
      return "boolean";
    case ValueType::Choice:
      return "string";
    case ValueType::Vector:
      return "[x, y]";
  }
  return "?";
}

std::span<const KeySpec> key_table() {
  return kKeys;
}

std::span<const SectionSpec> section_table() {
  return kSections;
}

const KeySpec* find_key(std::string_view section, std::string_view key) {
  for (const auto& k : kKeys)
    if (section == k.section && key == k.key) return &k;
  return nullptr;
}

const SectionSpec* find_section(std::string_view name) {
  for (const auto& s : kSections)
    if (name == s.name) return &s;
  return nullptr;
}

std::vector<std::string> keys_of(std::string_view section) {
  std::vector<std::string> out;
  for (const auto& k : kKeys)
    if (section == k.section) out.emplace_back(k.key);
  return out;
}

std::vector<std::string> section_names() {
  std::vector<std::string> out;
  for (const auto& s : kSections) out.emplace_back(s.name);
  return out;
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

std::string toml_number(double v) {
  char buf[64];
#ifdef __EMSCRIPTEN__
  // emscripten 3.1.6's libc++ has no floating-point std::to_chars: the shortest %g that
  // reads back to v (the web page; the same number, possibly spelt otherwise).
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  std::string t(buf);
#else
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  std::string t(buf, ec == std::errc() ? end : buf);
#endif
  const size_t e = t.find('e');
  if (e == std::string::npos) {
    if (t.find_first_of(".ni") == std::string::npos) t += ".0";  // "100" would be an integer
    return t;
  }
  // "1e+05" -> "1e5", "2.5e-07" -> "2.5e-7"
  std::string exponent = t.substr(e + 1);
  const bool negative = exponent[0] == '-';
  if (exponent[0] == '+' || exponent[0] == '-') exponent.erase(0, 1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return t.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
}

}  // namespace invfree::scene_io

namespace invfree {

std::vector<std::string> scene_keys() {
  std::vector<std::string> out;
  for (const auto& k : scene_io::key_table()) out.push_back(k.name());
  return out;
}

std::vector<SceneKeyInfo> scene_key_info() {
  const SceneDef defaults;
  std::vector<SceneKeyInfo> out;
  for (const auto& k : scene_io::key_table()) {
    SceneKeyInfo info{k.section,         k.key, scene_io::value_type_name(k.type), k.unit, "", {},
                      k.write(defaults), k.doc};
    for (const char* c : k.choices) info.choices.emplace_back(c);
    if (const ValueBounds* b = find_value_bounds(k.name())) info.range = b->range();
    out.push_back(std::move(info));
  }
  return out;
}

std::vector<SceneSectionInfo> scene_section_info() {
  std::vector<SceneSectionInfo> out;
  for (const auto& s : scene_io::section_table()) out.push_back({s.name, s.term != nullptr, s.doc});
  return out;
}

}  // namespace invfree
