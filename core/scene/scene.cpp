#include "scene/scene.h"

#include <cmath>
#include <cstdio>

#include "scene/initial_state.h"
#include "scene/scene_fields.h"
#include "shape/shape_mesh.h"
#include "shape/shape_region.h"

namespace invfree {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// The course's vector values: finite, a ground normal that is not zero, a positive stretch.
std::optional<SceneProblem> find_vector_problem(const SceneDef& s) {
  if (!s.ground_normal.allFinite()) return SceneProblem{"ground.normal", "must be finite", {}};
  if (!(s.ground_normal.norm() > 0.0))
    return SceneProblem{"ground.normal", "must not be zero (it is the plane's normal)", {}};
  if (!s.initial_stretch.allFinite() || !(s.initial_stretch.minCoeff() > 0.0))
    return SceneProblem{"initial.stretch", "both factors must be finite and > 0", {}};
  if (!s.fixed_box_min.allFinite()) return SceneProblem{"fixed.box_min", "must be finite", {}};
  if (!s.fixed_box_max.allFinite()) return SceneProblem{"fixed.box_max", "must be finite", {}};
  return std::nullopt;
}

// The course's chapter 0: particles (shape "points") take their mass from node_mass and
// their forces from [mass_spring] (they have no triangles); per-spring gravity counts
// springs.
std::optional<SceneProblem> find_course_problem(const SceneDef& s) {
  bool points = false;
  for (int k = 0; k < body_count(s); ++k)
    points = points || placed_body(s, k).shape.kind == ShapeKind::Points;
  if (points && !(s.node_mass > 0.0))
    return SceneProblem{"mesh.node_mass",
                        "shape \"points\" needs node_mass > 0 (a particle has no area to weigh)",
                        {"mesh.shape"}};
  if (points && !s.has_mass_spring)
    return SceneProblem{"mesh.shape",
                        "\"points\" has no triangles for [material]'s elasticity: add a "
                        "[mass_spring] section (springs, or none for free particles)",
                        {"mass_spring.enabled"}};
  if (points && s.has_contact())
    for (int k = 0; k < body_count(s); ++k)
      if (placed_body(s, k).shape.kind == ShapeKind::Points && !(body_edge_length(s, k) > 0.0))
        return SceneProblem{"mesh.max_edge",
                            "a single point has no edge length for the barrier's contact "
                            "area: give max_edge > 0",
                            {"ground.enabled", "ceiling.enabled", "mesh.points"}};
  if (s.has_gravity && s.gravity_per_spring && !s.has_mass_spring)
    return SceneProblem{
        "gravity.per_spring", "counts springs: it needs [mass_spring]", {"mass_spring.enabled"}};
  return std::nullopt;
}

}  // namespace

const char* integrator_name(Integrator i) {
  return enum_name(kIntegratorNames, i);
}

std::optional<Integrator> integrator_from_name(std::string_view name) {
  return enum_from_name(kIntegratorNames, name);
}

const char* fixed_corners_name(FixedCorners c) {
  return enum_name(kFixedCornersNames, c, "none");
}

std::optional<FixedCorners> fixed_corners_from_name(std::string_view name) {
  return enum_from_name(kFixedCornersNames, name);
}

double load_factor(const SceneDef& s, long step) {
  return step >= s.ramp_steps ? 1.0 : double(step) / double(s.ramp_steps);
}

bool self_contact_can_run(const SceneDef& s) {
  return !s.has_mass_spring && !s.has_fixed;
}

bool self_contact_by_default(const SceneDef& s) {
  return self_contact_can_run(s) && s.integrator != Integrator::SymplecticEuler;
}

bool SceneDef::self_contact_on() const {
  return has_self_contact && self_contact_can_run(*this);
}

int body_count(const SceneDef& s) {
  return s.bodies.empty() ? 1 : static_cast<int>(s.bodies.size());
}

PlacedBody placed_body(const SceneDef& s, int body) {
  PlacedBody b{s.side, s.n_seg, s.shape, Vec2::Zero(), s.initial_velocity, s.lame};
  if (s.bodies.empty()) return b;
  const BodyDef& d = s.bodies[body];
  b.side = d.side.value_or(s.side);
  b.n_seg = d.n_seg.value_or(s.n_seg);
  ShapeDef& shape = b.shape;
  shape.kind = d.shape.value_or(shape.kind);
  shape.width = d.width.value_or(shape.width);
  shape.height = d.height.value_or(shape.height);
  shape.radius = d.radius.value_or(shape.radius);
  shape.inner_radius = d.inner_radius.value_or(shape.inner_radius);
  shape.scale = d.scale.value_or(shape.scale);
  shape.max_edge = d.max_edge.value_or(shape.max_edge);
  if (d.outline) shape.outline = *d.outline;
  if (d.holes) shape.holes = *d.holes;
  if (d.path_id) shape.path_id = *d.path_id;
  // A body that names its own file (or path, or scale) carries what scene_io read from it.
  if (d.file || d.path_id || d.scale) {
    shape.file = d.file.value_or(shape.file);
    shape.loaded = d.loaded;
  }
  b.offset = d.offset;
  b.velocity = d.velocity.value_or(s.initial_velocity);
  b.lame = d.lame.value_or(s.lame);
  return b;
}

double body_edge_length(const SceneDef& s, int body) {
  const PlacedBody b = placed_body(s, body);
  if (b.shape.kind == ShapeKind::Square) return b.side / b.n_seg;
  return shape_max_edge(b.shape, b.n_seg);
}

void set_material_of_every_body(SceneDef& s, const Lame& lame) {
  s.lame = lame;
  for (BodyDef& b : s.bodies) b.lame.reset();
}

double SceneDef::contact_area() const {
  return body_edge_length(*this, 0);
}

Vec2 ground_unit_normal(const SceneDef& s) {
  return s.ground_normal.normalized();
}

bool ground_is_sloped(const SceneDef& s) {
  return !(s.ground_normal.x() == 0.0 && s.ground_normal.y() > 0.0);
}

double ground_gap(const SceneDef& s, double x, double y) {
  if (!ground_is_sloped(s)) return y - s.ground_y;
  const Vec2 n = ground_unit_normal(s);
  return n.x() * x + n.y() * (y - s.ground_y);
}

bool ValueBounds::contains(double v) const {
  return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string ValueBounds::range() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  char buf[64] = "";
  if (integer && has_lo && has_hi)
    std::snprintf(buf, sizeof buf, "%g to %g", lo, hi);
  else if (has_lo && has_hi)
    std::snprintf(buf, sizeof buf, "%c%g, %g%c", lo_open ? '(' : '[', lo, hi, hi_open ? ')' : ']');
  else if (has_lo)
    std::snprintf(buf, sizeof buf, "%s %g", lo_open ? ">" : ">=", lo);
  else if (has_hi)
    std::snprintf(buf, sizeof buf, "%s %g", hi_open ? "<" : "<=", hi);
  return buf;
}

std::string ValueBounds::requirement() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (integer && has_lo && has_hi) return "must be between " + number(lo) + " and " + number(hi);
  if (integer) return "must be " + range();
  if (has_lo && has_hi) return "must be in " + range();
  if (has_lo || has_hi) return "must be a finite number " + range();
  return "must be finite";
}

// Each [[body]]'s own values (scene_fields.h's body_fields), under the key "body.<key>"
// and a reason that names the body (1-based, as a reader counts the tables).
static std::optional<SceneProblem> find_body_problem(const SceneDef& s) {
  if (s.bodies.size() > static_cast<size_t>(kMaxBodies))
    return SceneProblem{"body", "at most " + std::to_string(kMaxBodies) + " [[body]] tables", {}};
  for (size_t k = 0; k < s.bodies.size(); ++k)
    for (const BodyField& f : body_fields()) {
      const std::optional<FieldValue> v = f.get ? f.get(s.bodies[k]) : std::nullopt;
      if (!v) continue;
      std::string why;
      if (const Vec2* u = std::get_if<Vec2>(&*v)) {
        if (!u->allFinite()) why = "must be finite";
      } else if (const ValueBounds* b = f.stands_for ? find_value_bounds(f.stands_for) : nullptr) {
        if (!b->contains(field_number(*v))) why = b->requirement();
      }
      if (!why.empty())
        return SceneProblem{
            std::string("body.") + f.key, why + " (in [[body]] " + std::to_string(k + 1) + ")", {}};
    }
  return std::nullopt;
}

// Each body's meshed shape (shape/shape_mesh.h): a file named where one is needed, then
// the mesher's verdict on the outline, its holes, the file's contents and max_edge, under
// "mesh.<key>" for the scene's one body and "body.<key>" for a [[body]].
static std::optional<SceneProblem> find_shape_problem(const SceneDef& s) {
  double nodes = 0.0;
  for (int k = 0; k < body_count(s); ++k) {
    const PlacedBody b = placed_body(s, k);
    if (b.shape.kind == ShapeKind::Square) continue;
    const std::string prefix = s.bodies.empty() ? "mesh." : "body.";
    const std::string where =
        s.bodies.empty() ? "" : " (in [[body]] " + std::to_string(k + 1) + ")";
    if ((b.shape.kind == ShapeKind::Svg || b.shape.kind == ShapeKind::MeshFile) &&
        b.shape.file.empty())
      return SceneProblem{
          prefix + "file",
          std::string("shape \"") + shape_kind_name(b.shape.kind) + "\" needs a file" + where,
          {prefix + "shape"}};
    const ShapeMeshResult r = mesh_shape(b.shape, shape_max_edge(b.shape, b.n_seg));
    if (!r.error.empty()) {
      // "outline: reason" -> key mesh.outline; "holes[1]: reason" keeps its "holes[1]: ",
      // which says which hole.
      const size_t colon = r.error.find(": ");
      std::string key = colon == std::string::npos ? "shape" : r.error.substr(0, colon);
      std::string reason = r.error;
      if (key.find('[') == std::string::npos && colon != std::string::npos)
        reason = r.error.substr(colon + 2);
      key = key.substr(0, key.find('['));
      // No causes: the message names the key at fault even when the user's last change
      // was mesh.shape ("--set mesh.shape=polygon: mesh.outline: edges 0 and 2 cross").
      return SceneProblem{prefix + key, reason + where, {}};
    }
    nodes += r.mesh.node_count();
  }
  if (nodes > 0.0)
    if (auto e = check_nodes_fit_in_memory(nodes); !e.empty())
      return SceneProblem{"mesh.max_edge", e, {"mesh.n_seg"}};
  return std::nullopt;
}

std::optional<SceneProblem> find_scene_problem(const SceneDef& s) {
  for (const SceneField& f : scene_fields())
    if (f.kept && (f.type == FieldType::Number || f.type == FieldType::Integer) &&
        !f.bounds.contains(field_number(f.get(s))))
      return SceneProblem{f.name(), f.bounds.requirement(), {}};
  if (auto problem = find_body_problem(s)) return problem;
  if (auto e = check_mesh_fits_in_memory(s); !e.empty()) return SceneProblem{"mesh.n_seg", e, {}};
  if (auto problem = find_shape_problem(s)) return problem;
  if (!s.initial_velocity.allFinite())
    return SceneProblem{"initial.velocity", "must be finite", {}};
  if (!s.gravity.allFinite()) return SceneProblem{"gravity.g", "must be finite", {}};
  if (auto problem = find_vector_problem(s)) return problem;
  if (auto problem = find_course_problem(s)) return problem;
  // Relations between switched-on terms.
  if (s.has_ceiling && s.has_ground) {
    const std::vector<std::string> planes = {"ground.y", "ground.enabled", "ceiling.enabled"};
    if (s.ceiling_y <= s.ground_y)
      return SceneProblem{"ceiling.y", "must be above ground.y", planes};
    if (s.ceiling_stop <= s.ground_y)
      return SceneProblem{"ceiling.stop", "must be above ground.y", planes};
  }
  if (s.is_static() && s.linear_solver == LinearSolverKind::Pcg)
    return SceneProblem{"solver.linear_solver",
                        "\"pcg\" needs inertia's lower bound of the Hessian, which a static "
                        "step has not (use \"auto\", \"ldlt\" or \"cholmod\")",
                        {"solver.integrator"}};
  return check_initial_state(s);
}

std::string validate_scene(const SceneDef& s) {
  const auto problem = find_scene_problem(s);
  return problem ? problem->key + ": " + problem->reason : "";
}

}  // namespace invfree
