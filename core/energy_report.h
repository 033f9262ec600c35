// The mechanical energies of a simulation's current state, each term apart, for plots and
// the CSV of `invfree simulate` (what a teacher shows: kinetic energy turning into elastic
// energy on impact, gravity's potential going down):
//   kinetic        1/2 sum_i m_i |v_i|^2
//   elastic        sum_t area_t Psi(F_t)             (potential/elasticity.h), or the
//                  springs' energy in a mass-spring scene (potential/mass_spring.h)
//   gravitational  -sum_i m_i g.x_i                  (potential/gravity.h; 0 at y = 0)
//   contact        the planes' barriers (potential/plane_barrier.h) and, with
//                  self-contact, the point-edge barriers (potential/self_contact_barrier.h);
//                  not scaled by h^2 as in the step's potential
// The step's incremental potential (StepReport::energy) is another quantity: it adds the
// inertia term and scales the rest by h^2.
#pragma once

#include "simulation.h"

namespace invfree {

struct EnergyReport {
  double kinetic = 0.0, elastic = 0.0, gravitational = 0.0, contact = 0.0;
  double total() const { return kinetic + elastic + gravitational + contact; }
};

EnergyReport energy_report(const Simulation& sim);

}  // namespace invfree
