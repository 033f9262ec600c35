// The methods the study and the stability sweep compare. Each is nothing but a
// set of scene settings, written as the `--set section.key=value` overrides a user would
// type, applied through the scene-file parser: no method has a code path of its own.
//   lecture            neo-Hookean, diagonal-space PSD projection, inversion-free filter
//   full-eigen-clamp   the same, clamping each triangle's whole 6x6 Hessian instead
//   no-projection      the same, plain Newton on the indefinite Hessian
//   no-inversion-filter the same, with only backtracking (no det F > 0 step bound)
//   symplectic-euler   explicit, on the same energies, `substeps` steps per scene step
//   linear, arap, stable-neo-hookean  the invertible models, lecture's solver settings
// Every one of them switches the course's springs off (mass_spring.enabled=false), so a
// course scene's springs do not leak into a neo-Hookean row. The stability sweep adds
// rows the study does not take (stability_methods()):
//   mass-spring        the course's springs instead of the triangles, with the scene's k
//                      (the stress scenes: the default 1e5 N/m, the base square's E per unit
//                      thickness), lecture's solver settings: nothing resists a triangle's
//                      collapse, so a squash inverts it where neo-Hookean holds
//   no-ccd             the lecture's row with self-contact but without the line search's
//                      CCD bound (only the barrier's energy checks stop a step): where a
//                      step jumps a node across an edge the run ends `intersected`; n/a on
//                      scenes without self-contact
#pragma once

#include <span>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace invfree {

struct Method {
  const char* name;                    // CSV/table key
  const char* label;                   // legend text
  std::vector<const char*> overrides;  // every solver/model key, so no scene setting leaks in
                                       // (material parameters E, nu, k: the scene's)
  int substeps = 1;  // steps per scene step in the stability sweep (explicit: tiny steps)
  bool self_contact_only = false;  // n/a on a scene without self-contact
  bool implicit() const { return substeps == 1; }
};

std::span<const Method> study_methods();
// study_methods() and, after them, the rows only the stability sweep runs (mass-spring: a
// verdict teaches there, an error against its own reference in the study would not).
std::span<const Method> stability_methods();
const Method* find_method(const std::string& name);

// The material model the method sets ("neo-hookean", "linear", ..., "mass-spring"): methods of one
// model share one reference in the study, so only their errors compare with each other.
std::string method_model(const Method& method);

// The method's model may invert by design (linear, ARAP, stable neo-Hookean: energies
// finite at det F <= 0), so the stability sweep marks an inversion as allowed, not as a
// failure. Not the springs: a triangle folding through under them is the course's lesson.
bool inversion_allowed(const Method& method);

// The scene with the method's settings applied (time.h is divided by `substeps` when
// `with_substeps`). Returns "" or the parser's error.
std::string apply_method(const Method& method, SceneDef& scene, bool with_substeps);

// `--methods a,b,c`: the names, each one of `allowed`, in `allowed`'s order, into `out`
// ("" leaves `out` empty: every method). Returns "" or a one-line error naming the
// unknown name and the choices.
std::string parse_method_list(const std::string& text, std::span<const Method> allowed,
                              std::vector<std::string>* out);

// The method's settings as a command line fragment, e.g. "--set solver.projection=full".
std::string method_command_line(const Method& method);

}  // namespace invfree
