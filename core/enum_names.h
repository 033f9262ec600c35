// The one idiom of every enum <-> string map of the project: a constexpr array of
// {value, name} pairs beside the enum, and two lookups over it. A name is a scene file's
// spelling ("neo-hookean"); the arrays are also the choices of string keys
// (scene/scene_fields.h). Dependency-free, beside types.h at the bottom of the core, so any
// folder may include it.
#pragma once

#include <optional>
#include <string_view>

namespace invfree {

template <class E>
struct EnumName {
  E value;
  const char* name;
};

// The name of `value` in `names` (an array or span of EnumName), `unknown` when absent.
template <class Names, class E>
constexpr const char* enum_name(const Names& names, E value, const char* unknown = "?") {
  for (const auto& n : names)
    if (n.value == value) return n.name;
  return unknown;
}

// The value spelt `name` in `names`, nullopt when none is.
template <class Names>
constexpr auto enum_from_name(const Names& names, std::string_view name)
    -> std::optional<decltype(std::begin(names)->value)> {
  for (const auto& n : names)
    if (name == n.name) return n.value;
  return std::nullopt;
}

}  // namespace invfree
