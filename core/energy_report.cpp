#include "energy_report.h"

#include "potential/elasticity.h"
#include "potential/gravity.h"
#include "potential/plane_barrier.h"

namespace invfree {

EnergyReport energy_report(const Simulation& sim) {
  const SceneDef& s = sim.scene;
  EnergyReport e;
  e.elastic = elastic_energy(sim.mesh, s.model, s.lame, sim.x);
  const Gravity gravity{s.has_gravity, s.gravity};
  const BarrierParams barrier{s.dhat, s.kappa, s.contact_area()};
  const GroundBarrier ground{s.has_ground, s.ground_y, barrier};
  const CeilingBarrier ceiling{s.has_ceiling, barrier};
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    const NodeState node{i, sim.x[2 * i], sim.x[2 * i + 1], sim.node_mass[i], 0.0, sim.ceiling_y};
    e.kinetic += 0.5 * sim.node_mass[i] * sim.v.segment<2>(2 * i).squaredNorm();
    if (gravity.on) e.gravitational += gravity.value(node);
    if (ground.on) e.contact += ground.value(node);
    if (ceiling.on) e.contact += ceiling.value(node);
  }
  return e;
}

}  // namespace invfree
