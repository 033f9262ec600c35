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
// Each is the sum of the terms of its kind (potential/term.h's EnergyKind) in the step's
// list of terms, built by core/make_terms.cpp at the current state; friction and the
// control terms (the ceiling's penalty, the grab) are not energies of the bodies.
#pragma once

#include "potential/incremental_potential.h"
#include "simulation.h"

namespace invfree {

struct EnergyReport {
  double kinetic = 0.0, elastic = 0.0, gravitational = 0.0, contact = 0.0;
  double total() const { return kinetic + elastic + gravitational + contact; }
};

enum class EnergyReportParts { All, WithoutContact };
EnergyReport energy_report(const Simulation& sim,
                           EnergyReportParts parts = EnergyReportParts::All);
// The same from terms already built at the state z = [x; c] with velocities v (a step's
// own problem: no allocation).
EnergyReport energy_report_of(const StepProblem& p, StepCaches& caches, const VecX& z,
                              const VecX& v);

}  // namespace invfree
