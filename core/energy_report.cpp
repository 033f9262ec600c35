#include "energy_report.h"

#include "make_terms.h"
#include "potential/term_sums.h"

namespace invfree {

EnergyReport energy_report_of(const StepProblem& p, StepCaches& caches, const VecX& z,
                              const VecX& v) {
  EnergyReport e;
  for (int i = 0; i < p.node_count(); ++i)
    e.kinetic += 0.5 * (*p.mass)[i] * v.segment<2>(2 * i).squaredNorm();
  EnergyBins bins;
  begin_terms(p, caches, z);  // self-contact's candidates at z
  energies_by_kind(p, caches, z, bins);
  e.elastic = bins[EnergyKind::Elastic];
  e.gravitational = bins[EnergyKind::Gravity];
  e.contact = bins[EnergyKind::Contact];
  return e;
}

EnergyReport energy_report(const Simulation& sim, EnergyReportParts parts) {
  const SceneDef& s = sim.scene;
  const bool contact = parts == EnergyReportParts::All;
  Boundary scratch;  // the live window calls this every frame: the step's boundary serves
  const Boundary* boundary = contact && s.self_contact_on() ? &boundary_now(sim, scratch) : nullptr;
  StepProblem p;
  StepCaches caches;
  make_terms(sim, boundary, p, caches);
  const int n = sim.mesh.node_count();
  VecX z(p.dof_count());
  z.head(2 * n) = sim.x;
  if (p.ceiling.on) z[2 * n] = sim.ceiling_y;
  EnergyReport e = energy_report_of(p, caches, z, sim.v);
  if (!contact) e.contact = 0.0;
  return e;
}

}  // namespace invfree
