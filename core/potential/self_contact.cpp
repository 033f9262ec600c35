#include "potential/self_contact.h"

namespace invfree {

double self_contact_value(const SelfContact& c, const VecX& z, const VecX& x_start) {
  const SelfContactTimer timer{c.cache->ms};
  double e = self_contact_energy(*c.boundary, *c.rest, c.cache->pairs, z, c.params);
  if (!c.cache->friction.empty()) e += self_friction_energy(c.cache->friction, z, x_start, c.eps_u);
  return e;
}

void self_contact_derivatives(const SelfContact& c, const VecX& z, const VecX& x_start,
                              double scale, VecX& gradient) {
  const SelfContactTimer timer{c.cache->ms};
  c.cache->hessians.clear();
  add_self_contact_gradient_hessian(*c.boundary, *c.rest, c.cache->pairs, z, c.params, scale,
                                    gradient, c.cache->hessians);
  if (!c.cache->friction.empty())
    add_self_friction_gradient_hessian(c.cache->friction, z, x_start, c.eps_u, scale, gradient,
                                       c.cache->hessians);
}

}  // namespace invfree
