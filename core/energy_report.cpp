#include "energy_report.h"

#include "collision/broad_phase.h"
#include "potential/elasticity.h"
#include "potential/gravity.h"
#include "potential/mass_spring.h"
#include "potential/plane_barrier.h"
#include "potential/self_contact_barrier.h"
#include "solver/step_workspace.h"

namespace invfree {

EnergyReport energy_report(const Simulation& sim) {
  const SceneDef& s = sim.scene;
  EnergyReport e;
  if (s.has_triangle_elasticity())
    e.elastic = elastic_energy(sim.mesh, s.model, s.lame, sim.x, sim.triangle_lame);
  if (s.has_mass_spring && sim.workspace) {
    const MassSpring springs{true, s.spring_stiffness, true, &sim.workspace->springs, nullptr};
    e.elastic += mass_spring_energy(springs, sim.x.data());
  }
  const Gravity gravity{s.has_gravity, s.gravity};
  const GroundBarrier ground = ground_barrier_of(sim);
  const CeilingBarrier ceiling = ceiling_barrier_of(sim);
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    const NodeState node{i, sim.x[2 * i], sim.x[2 * i + 1], sim.node_mass[i], 0.0, sim.ceiling_y};
    e.kinetic += 0.5 * sim.node_mass[i] * sim.v.segment<2>(2 * i).squaredNorm();
    if (gravity.on) e.gravitational += gravity.value(node);
    if (ground.on) e.contact += ground.value(node);
    if (ceiling.on) e.contact += ceiling.value(node);
  }
  if (s.has_self_contact) {
    Boundary scratch;  // the live window calls this every frame: the step's boundary serves
    const Boundary& boundary = boundary_now(sim, scratch);
    std::vector<PointEdgePair> pairs;
    BroadPhaseGrid grid;
    point_edge_candidates(boundary, sim.x, s.dhat, grid, pairs);
    e.contact += self_contact_energy(boundary, sim.mesh.rest, pairs, sim.x, {s.dhat, s.kappa});
  }
  return e;
}

}  // namespace invfree
