#include "app/study/methods.h"

#include <algorithm>

#include "scene_io/scene_file.h"

namespace invfree {

namespace {

const std::vector<Method>& table() {
  static const std::vector<Method> methods = {
      {"lecture",
       "lecture: diagonal-space projection + inversion filter (+ Newton safeguards)",
       {"material.model=neo-hookean", "solver.projection=diagonal", "solver.inversion_filter=true",
        "solver.integrator=implicit-euler", "solver.step_expansion=true",
        "solver.friction_crossing_stop=true", "mass_spring.enabled=false"}},
      {"plain-line-search",
       "lecture without Newton's safeguards (halving only)",
       {"material.model=neo-hookean", "solver.projection=diagonal", "solver.inversion_filter=true",
        "solver.integrator=implicit-euler", "solver.step_expansion=false",
        "solver.friction_crossing_stop=false", "mass_spring.enabled=false"}},
      {"full-eigen-clamp",
       "6x6 eigenvalue clamp + inversion filter",
       {"material.model=neo-hookean", "solver.projection=full", "solver.inversion_filter=true",
        "solver.integrator=implicit-euler", "solver.step_expansion=true",
        "solver.friction_crossing_stop=true", "mass_spring.enabled=false"}},
      {"no-projection",
       "no projection (plain Newton) + inversion filter",
       {"material.model=neo-hookean", "solver.projection=none", "solver.inversion_filter=true",
        "solver.integrator=implicit-euler", "solver.step_expansion=true",
        "solver.friction_crossing_stop=true", "mass_spring.enabled=false"}},
      {"no-inversion-filter",
       "diagonal projection, backtracking only",
       {"material.model=neo-hookean", "solver.projection=diagonal", "solver.inversion_filter=false",
        "solver.integrator=implicit-euler", "solver.step_expansion=true",
        "solver.friction_crossing_stop=true", "mass_spring.enabled=false"}},
      {"symplectic-euler",
       "symplectic Euler (explicit), neo-Hookean",
       {"material.model=neo-hookean", "solver.projection=diagonal", "solver.inversion_filter=true",
        "solver.integrator=symplectic-euler", "solver.step_expansion=true",
        "solver.friction_crossing_stop=true", "mass_spring.enabled=false"},
       20},
      {"linear",
       "linear elasticity, projected Newton",
       {"material.model=linear", "solver.projection=diagonal", "solver.inversion_filter=true",
        "solver.integrator=implicit-euler", "solver.step_expansion=true",
        "solver.friction_crossing_stop=true", "mass_spring.enabled=false"}},
      {"arap",
       "ARAP, projected Newton",
       {"material.model=arap", "solver.projection=diagonal", "solver.inversion_filter=true",
        "solver.integrator=implicit-euler", "solver.step_expansion=true",
        "solver.friction_crossing_stop=true", "mass_spring.enabled=false"}},
      {"stable-neo-hookean",
       "stable neo-Hookean, projected Newton",
       {"material.model=stable-neo-hookean", "solver.projection=diagonal",
        "solver.inversion_filter=true", "solver.integrator=implicit-euler",
        "solver.step_expansion=true", "solver.friction_crossing_stop=true",
        "mass_spring.enabled=false"}},
      // Stability only (stability_methods()): keep it after every study method.
      {"mass-spring",
       "mass-spring (the course's springs, the scene's k), projected Newton",
       {"mass_spring.enabled=true", "solver.projection=diagonal", "solver.inversion_filter=true",
        "solver.integrator=implicit-euler", "solver.step_expansion=true",
        "solver.friction_crossing_stop=true"}},
      {"no-ccd",
       "lecture without the CCD step bound (self-contact scenes only)",
       {"material.model=neo-hookean", "solver.projection=diagonal", "solver.inversion_filter=true",
        "solver.integrator=implicit-euler", "solver.step_expansion=true",
        "solver.friction_crossing_stop=true", "mass_spring.enabled=false",
        "self_contact.ccd=false"},
       1,
       true},
  };
  return methods;
}

// The table's rows before the first one the study does not take.
size_t study_method_count() {
  size_t n = 0;
  while (n < table().size() && std::string(table()[n].name) != "mass-spring") ++n;
  return n;
}

}  // namespace

std::span<const Method> study_methods() {
  return std::span<const Method>(table()).first(study_method_count());
}

std::span<const Method> stability_methods() {
  return table();
}

const Method* find_method(const std::string& name) {
  for (const Method& m : table())
    if (name == m.name) return &m;
  return nullptr;
}

std::string method_model(const Method& method) {
  for (const char* o : method.overrides)
    if (std::string(o) == "mass_spring.enabled=true") return "mass-spring";
  const std::string key = "material.model=";
  for (const char* o : method.overrides)
    if (std::string(o).starts_with(key)) return std::string(o).substr(key.size());
  return "";
}

bool inversion_allowed(const Method& method) {
  const std::string model = method_model(method);
  return model == "linear" || model == "arap" || model == "stable-neo-hookean";
}

std::string apply_method(const Method& method, SceneDef& scene, bool with_substeps) {
  if (method.self_contact_only && !scene.self_contact_on())
    return "the scene has no self-contact, so nothing to take the CCD from";
  // The method's overrides together, validated once (scene_io/scene_file.h).
  const std::vector<std::string> overrides(std::begin(method.overrides),
                                           std::end(method.overrides));
  if (std::string e = apply_overrides(scene, overrides); !e.empty()) return e;
  if (with_substeps) scene.h /= method.substeps;
  return "";
}

std::string parse_method_list(const std::string& text, std::span<const Method> allowed,
                              std::vector<std::string>* out) {
  out->clear();
  std::vector<std::string> names;
  size_t begin = 0;
  while (begin <= text.size() && !text.empty()) {
    const size_t end = std::min(text.find(',', begin), text.size());
    names.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  std::string choices;
  for (const Method& m : allowed) choices += std::string(choices.empty() ? "" : ", ") + m.name;
  for (const std::string& n : names) {
    const bool known =
        std::any_of(allowed.begin(), allowed.end(), [&](const Method& m) { return n == m.name; });
    if (!known) return "--methods: unknown method '" + n + "' (one of: " + choices + ")";
  }
  for (const Method& m : allowed)
    if (std::find(names.begin(), names.end(), m.name) != names.end()) out->push_back(m.name);
  return "";
}

std::string method_command_line(const Method& method) {
  std::string s;
  for (const char* o : method.overrides) s += std::string(s.empty() ? "" : " ") + "--set " + o;
  return s;
}

}  // namespace invfree
