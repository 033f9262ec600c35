// Material models, Lame parameters and the per-model dispatch. Each model lives in its
// own header as a struct of static functions (value, first Piola stress, stress
// derivative); `visit_model` turns the runtime enum into a compile-time type once per
// loop, so hot loops never branch on the model per triangle.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "enum_names.h"

namespace invfree {

enum class Model { NeoHookean, Linear, Arap, StableNeoHookean };

// How the elastic Hessian is made positive semi-definite before the Newton solve.
enum class HessianProjection {
  Diagonal,  // the lecture: clamp the A block and the flip/twist eigenvalues (default)
  Full,      // clamp the eigenvalues of each triangle's whole 6x6 Hessian
  None       // exact, possibly indefinite Hessian (plain Newton)
};
inline constexpr EnumName<HessianProjection> kProjectionNames[] = {
    {HessianProjection::Diagonal, "diagonal"},
    {HessianProjection::Full, "full"},
    {HessianProjection::None, "none"}};

struct Lame {
  double mu = 0.0;
  double lambda = 0.0;
  bool operator==(const Lame&) const = default;
};

// The reference demo's (3D) conversion: mu = E / (2(1+nu)), lambda = E nu / ((1+nu)(1-2nu)).
Lame lame_from_young_poisson(double youngs, double poisson);
// Inverse of the above; valid for mu > 0, lambda >= 0.
void young_poisson_from_lame(const Lame& lame, double* youngs, double* poisson);

// Invertible models accept det F <= 0; neo-Hookean needs det F > 0 (it is a barrier).
bool model_allows_inversion(Model m);
// A model's names come from its entry in kModels (material/models.h).
const char* model_name(Model m);   // the scene-file spelling, e.g. "neo-hookean"
const char* model_label(Model m);  // for people, e.g. "neo-Hookean"
std::optional<Model> model_from_name(std::string_view name);
std::span<const EnumName<Model>> model_names();  // every model, in the enum's order
const char* projection_name(HessianProjection p);
std::optional<HessianProjection> projection_from_name(std::string_view name);

}  // namespace invfree
