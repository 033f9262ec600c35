#include "app/live/method_choice.h"

namespace invfree::live {

namespace {

constexpr LiveMethod kMethods[] = {{"lecture", "the lecture's method"},
                                   {"no-projection", "no projection (plain Newton)"},
                                   {"no-inversion-filter", "no inversion filter"},
                                   {"symplectic-euler", "symplectic Euler (explicit)"},
                                   {"linear", "linear elasticity"}};

}  // namespace

std::span<const LiveMethod> live_methods() {
  return kMethods;
}

const Method* current_method(const SceneDef& s) {
  for (const LiveMethod& lm : kMethods) {
    const Method* m = find_method(lm.name);
    SceneDef with = s;
    if (m && apply_method(*m, with, false).empty() && with == s) return m;
  }
  return nullptr;
}

std::string switch_method(const SceneDef& current, const Method& to, SceneDef* out) {
  SceneDef next = current;
  if (std::string e = apply_method(to, next, false); !e.empty()) return e;
  const Method* from = current_method(current);
  const int from_substeps = from ? from->substeps : 1;
  next.h = current.h * from_substeps / to.substeps;
  *out = next;
  return "";
}

std::string solver_caption(const SceneDef& s) {
  if (s.integrator == Integrator::SymplecticEuler) return "symplectic Euler (explicit)";
  std::string c = s.integrator == Integrator::Static ? "static, Newton" : "implicit Euler, Newton";
  switch (s.projection) {
    case HessianProjection::Diagonal:
      c += " + diagonal-space projection";
      break;
    case HessianProjection::Full:
      c += " + 6x6 eigenvalue clamp";
      break;
    case HessianProjection::None:
      c += ", no projection";
      break;
  }
  c += s.inversion_filter ? ", inversion filter" : ", no inversion filter";
  return c;
}

}  // namespace invfree::live
