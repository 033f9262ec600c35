// Runtime-to-compile-time dispatch over the material models: call `fn` with a value of
// the model's struct type (NeoHookean, LinearElasticity, Arap, StableNeoHookean).
#pragma once

#include "material/arap.h"
#include "material/linear_elasticity.h"
#include "material/material.h"
#include "material/neo_hookean.h"
#include "material/stable_neo_hookean.h"

namespace invfree {

template <class Fn>
decltype(auto) visit_model(Model m, Fn&& fn) {
  switch (m) {
    case Model::Linear:
      return fn(LinearElasticity{});
    case Model::Arap:
      return fn(Arap{});
    case Model::StableNeoHookean:
      return fn(StableNeoHookean{});
    case Model::NeoHookean:
    default:
      return fn(NeoHookean{});
  }
}

// Convenience wrappers for tests and tools (not for hot loops).
inline double energy_density(Model m, const Mat2& F, const Lame& l) {
  return visit_model(m, [&](auto model) { return decltype(model)::energy_density(F, l); });
}
inline Mat2 first_piola(Model m, const Mat2& F, const Lame& l) {
  return visit_model(m, [&](auto model) { return decltype(model)::first_piola(F, l); });
}
inline Mat4 stress_derivative(Model m, const Mat2& F, const Lame& l, bool project) {
  return visit_model(m,
                     [&](auto model) { return decltype(model)::stress_derivative(F, l, project); });
}

}  // namespace invfree
