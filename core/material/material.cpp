#include "material/material.h"

namespace invfree {

Lame lame_from_young_poisson(double youngs, double poisson) {
  return {0.5 * youngs / (1.0 + poisson),
          youngs * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson))};
}

void young_poisson_from_lame(const Lame& lame, double* youngs, double* poisson) {
  const double mu = lame.mu, lambda = lame.lambda;
  *poisson = lambda / (2.0 * (lambda + mu));
  *youngs = mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
}

bool model_allows_inversion(Model m) {
  return m != Model::NeoHookean;
}

namespace {
struct ModelName {
  Model model;
  const char* name;
};
constexpr ModelName kModelNames[] = {{Model::NeoHookean, "neo-hookean"},
                                     {Model::Linear, "linear"},
                                     {Model::Arap, "arap"},
                                     {Model::StableNeoHookean, "stable-neo-hookean"}};
struct ProjectionName {
  HessianProjection projection;
  const char* name;
};
constexpr ProjectionName kProjectionNames[] = {{HessianProjection::Diagonal, "diagonal"},
                                               {HessianProjection::Full, "full"},
                                               {HessianProjection::None, "none"}};
}  // namespace

const char* model_name(Model m) {
  for (const auto& e : kModelNames)
    if (e.model == m) return e.name;
  return "?";
}

std::optional<Model> model_from_name(std::string_view name) {
  for (const auto& e : kModelNames)
    if (name == e.name) return e.model;
  return std::nullopt;
}

const char* projection_name(HessianProjection p) {
  for (const auto& e : kProjectionNames)
    if (e.projection == p) return e.name;
  return "?";
}

std::optional<HessianProjection> projection_from_name(std::string_view name) {
  for (const auto& e : kProjectionNames)
    if (name == e.name) return e.projection;
  return std::nullopt;
}

}  // namespace invfree
