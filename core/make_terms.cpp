#include "make_terms.h"

#include <algorithm>
#include <limits>

#include "solver/step_workspace.h"

namespace invfree {

namespace {

constexpr double kCeilingInitialStiffness = 1000.0;  // the demo's DBC_stiff, times the mass

BarrierParams barrier_params(const SceneDef& s) {
  return {s.dhat, s.kappa, s.contact_area()};
}

void make_friction(const Simulation& sim, StepProblem& p) {
  const SceneDef& s = sim.scene;
  const int n = sim.mesh.node_count();
  GroundFriction& f = p.friction;
  f.on = s.has_ground && s.friction > 0.0;
  f.sloped = p.ground.sloped;
  f.tangent = Vec2(p.ground.normal.y(), -p.ground.normal.x());
  f.mu = s.friction;
  f.ground = p.ground;
  if (!f.on) return;
  f.weight.resize(n);
  for (int i = 0; i < n; ++i)
    f.weight[i] =
        friction_weight(s.friction, ground_gap(s, sim.x[2 * i], sim.x[2 * i + 1]), p.ground.at(i));
  f.eps_u = kFrictionEpsV * s.h;
}

void make_ceiling(const Simulation& sim, StepProblem& p) {
  const SceneDef& s = sim.scene;
  p.ceiling = ceiling_barrier_of(sim);
  CeilingPenalty& penalty = p.ceiling_penalty;
  penalty.on = p.ceiling.on;
  if (!penalty.on) return;
  penalty.target = next_ceiling_nominal(s, sim.ceiling_nominal);
  // Warm start: the stiffness the last step needed (state), at least the demo's initial
  // value; restarting from the initial value let a stiff square (E = 1e8) push the
  // ceiling back up every step and spend Newton's budget re-doubling k.
  penalty.stiffness = std::max(kCeilingInitialStiffness * sim.ceiling_mass, sim.ceiling_stiffness);
  penalty.fixed = false;
}

// Self-contact: friction lagged at x^n (from the candidates there).
void make_self_contact(const Simulation& sim, const Boundary* boundary, StepProblem& p,
                       StepCaches& caches) {
  const SceneDef& s = sim.scene;
  SelfContact& c = p.self_contact;
  caches.contact.ms = 0.0;
  c.on = s.self_contact_on() && boundary;
  if (!c.on) return;
  c.boundary = boundary;
  c.rest = &sim.mesh.rest;
  c.params = {s.dhat, s.kappa};
  c.ccd = s.self_contact_ccd;
  c.eps_u = kFrictionEpsV * s.h;
  caches.contact.pairs.clear();
  caches.contact.friction.clear();
  if (!(s.self_friction > 0.0)) return;  // Newton's begin and filters gather the candidates
  c.begin({sim.x, sim.mesh, sim.x, caches});
  lag_self_friction(*boundary, *c.rest, caches.contact.pairs, sim.x, c.params, s.self_friction,
                    caches.contact.friction);
}

}  // namespace

void make_terms(const Simulation& sim, const Boundary* boundary, StepProblem& p,
                StepCaches& caches) {
  const SceneDef& s = sim.scene;
  const int n = sim.mesh.node_count();
  p.mesh = &sim.mesh;
  p.mass = &sim.node_mass;
  p.h = s.h;
  p.x_start = sim.x;
  p.x_tilde = sim.x + s.h * sim.v;
  p.inertia = !s.is_static();
  p.energy_rounding = 0.0;
  if (s.is_static() && s.has_triangle_elasticity()) {
    double mu_area = 0.0;
    for (int t = 0; t < sim.mesh.triangle_count(); ++t)
      mu_area +=
          sim.mesh.rest_area[t] * (sim.triangle_lame.empty() ? s.lame.mu : sim.triangle_lame[t].mu);
    p.energy_rounding = 8.0 * std::numeric_limits<double>::epsilon() * s.h * s.h * mu_area;
  }
  const double factor = load_factor(s, sim.step_count + 1);
  p.elasticity = {s.model, s.lame, s.projection, s.inversion_filter, s.has_triangle_elasticity()};
  p.elasticity.triangle_lame = sim.triangle_lame.empty() ? nullptr : sim.triangle_lame.data();
  p.springs.on = s.has_mass_spring && sim.workspace;
  p.springs.stiffness = s.spring_stiffness;
  p.springs.project = s.projection != HessianProjection::None;
  p.springs.hooke = s.spring_law == SpringLaw::Hooke;
  if (sim.workspace) {
    p.springs.springs = &sim.workspace->springs;
    p.springs.slots = &sim.workspace->spring_slots;
  }
  p.gravity = {s.has_gravity, factor * s.gravity};
  if (s.gravity_per_spring && sim.workspace &&
      sim.workspace->spring_count.size() == static_cast<size_t>(n))
    p.gravity.weight = sim.workspace->spring_count.data();
  p.dead_load.on = sim.node_load.size() == 2 * n;
  p.dead_load.force = sim.node_load.data();
  p.dead_load.origin = sim.mesh.rest.data();
  p.dead_load.factor = factor;
  p.pressure.on = !sim.pressure_edges.empty();
  p.pressure.edges = &sim.pressure_edges;
  p.pressure.factor = factor;
  p.pressure.project = s.projection != HessianProjection::None;
  p.ground = ground_barrier_of(sim);
  make_friction(sim, p);
  make_ceiling(sim, p);
  p.pull = sim.pull;
  p.pull.on = sim.pull.on && sim.pull.node >= 0 && sim.pull.node < n &&
              sim.pull.target.allFinite() && sim.pull.stiffness > 0.0;
  make_self_contact(sim, boundary, p, caches);
}

double next_ceiling_nominal(const SceneDef& s, double nominal) {
  return nominal > s.ceiling_stop ? nominal + s.h * s.ceiling_velocity : nominal;
}

GroundBarrier ground_barrier_of(const Simulation& sim) {
  const SceneDef& s = sim.scene;
  GroundBarrier g{s.has_ground, s.ground_y, barrier_params(s)};
  g.sloped = ground_is_sloped(s);
  g.normal = ground_unit_normal(s);
  g.node_area = sim.node_contact_area.empty() ? nullptr : sim.node_contact_area.data();
  return g;
}

CeilingBarrier ceiling_barrier_of(const Simulation& sim) {
  return {sim.scene.has_ceiling, barrier_params(sim.scene),
          sim.node_contact_area.empty() ? nullptr : sim.node_contact_area.data()};
}

const Boundary& boundary_now(const Simulation& sim, Boundary& scratch) {
  if (sim.workspace && !sim.workspace->boundary.edges.empty()) return sim.workspace->boundary;
  scratch = find_boundary(sim.mesh);
  return scratch;
}

}  // namespace invfree
