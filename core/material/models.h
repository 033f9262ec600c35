// The material models, one tuple: each entry carries the model's struct type (NeoHookean,
// LinearElasticity, Arap, StableNeoHookean: value, first Piola stress, stress derivative),
// its enum value, its scene-file name and its label (the frame and the live panel). Adding a
// model: its header, an enum value (material.h) and one entry here; `visit_model`, the names
// (model_name, model_from_name, the scene key's choices) and the labels follow.
#pragma once

#include <array>
#include <cstddef>
#include <tuple>

#include "material/arap.h"
#include "material/linear_elasticity.h"
#include "material/material.h"
#include "material/neo_hookean.h"
#include "material/stable_neo_hookean.h"
#include "enum_names.h"

namespace invfree {

template <class M, Model K>
struct ModelEntry {
  using Type = M;
  static constexpr Model kind = K;
  const char* name;   // the scene-file spelling, "neo-hookean"
  const char* label;  // for people, "neo-Hookean"
};

// In the enum's order (the scene key's choices are listed so). The first is visit_model's
// fallback.
inline constexpr std::tuple kModels{
    ModelEntry<NeoHookean, Model::NeoHookean>{"neo-hookean", "neo-Hookean"},
    ModelEntry<LinearElasticity, Model::Linear>{"linear", "linear"},
    ModelEntry<Arap, Model::Arap>{"arap", "ARAP"},
    ModelEntry<StableNeoHookean, Model::StableNeoHookean>{"stable-neo-hookean",
                                                          "stable neo-Hookean"},
};

// The models' {value, name} and {value, label} pairs (enum_names.h).
inline constexpr auto kModelNames = std::apply(
    [](const auto&... m) {
      return std::array{EnumName<Model>{m.kind, m.name}...};
    },
    kModels);
inline constexpr auto kModelLabels = std::apply(
    [](const auto&... m) {
      return std::array{EnumName<Model>{m.kind, m.label}...};
    },
    kModels);

namespace detail {
template <std::size_t I, class Fn>
decltype(auto) visit_model_from(Model m, Fn& fn) {
  if constexpr (I == std::tuple_size_v<decltype(kModels)>) {
    return fn(typename std::tuple_element_t<0, decltype(kModels)>::Type{});
  } else {
    using Entry = std::tuple_element_t<I, decltype(kModels)>;
    if (m == Entry::kind) return fn(typename Entry::Type{});
    return visit_model_from<I + 1>(m, fn);
  }
}
}  // namespace detail

// Runtime-to-compile-time dispatch over the models: calls `fn` with a value of the model's
// struct type (an unknown value: the first model's), so hot loops never branch on the
// model per triangle.
template <class Fn>
decltype(auto) visit_model(Model m, Fn&& fn) {
  return detail::visit_model_from<1>(m, fn);
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
