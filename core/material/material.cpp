#include "material/material.h"

#include "material/models.h"

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

const char* model_name(Model m) {
  return enum_name(kModelNames, m);
}

const char* model_label(Model m) {
  return enum_name(kModelLabels, m);
}

std::optional<Model> model_from_name(std::string_view name) {
  return enum_from_name(kModelNames, name);
}

std::span<const EnumName<Model>> model_names() {
  return kModelNames;
}

const char* projection_name(HessianProjection p) {
  return enum_name(kProjectionNames, p);
}

std::optional<HessianProjection> projection_from_name(std::string_view name) {
  return enum_from_name(kProjectionNames, name);
}

}  // namespace invfree
