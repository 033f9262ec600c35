#include "simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <type_traits>

#include "collision/intersection_check.h"
#include "scene/fixed_nodes.h"
#include "scene/initial_state.h"
#include "scene/scene_mesh.h"
#include "solver/self_contact_filter.h"
#include "solver/step_workspace.h"

namespace invfree {

Simulation::Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;
Simulation::~Simulation() = default;

namespace {

constexpr double kCeilingInitialStiffness = 1000.0;  // the demo's DBC_stiff, times the mass

BarrierParams barrier_params(const SceneDef& s) {
  return {s.dhat, s.kappa, s.contact_area()};
}

double next_ceiling_nominal(const SceneDef& s, double nominal) {
  return nominal > s.ceiling_stop ? nominal + s.h * s.ceiling_velocity : nominal;
}

// Checks the state a step produced: finite, no inversion when the model forbids it, every
// node strictly between the planes. Returns Ok or the first violation found.
StepStatus check_invariants(const Simulation& sim, const VecX& x, const VecX& v, double ceiling,
                            std::string* message) {
  if (!x.allFinite() || !v.allFinite() || !std::isfinite(ceiling)) {
    *message = "non-finite positions or velocities";
    return StepStatus::NonFinite;
  }
  const SceneDef& s = sim.scene;
  const int n = sim.mesh.node_count();
  for (int i = 0; i < n; ++i) {
    const double y = x[2 * i + 1];
    if ((s.has_ground && !(ground_gap(s, x[2 * i], y) > 0.0)) ||
        (s.has_ceiling && !(y < ceiling))) {
      *message = "node " + std::to_string(i) + " reached or crossed a plane";
      return StepStatus::Penetrated;
    }
  }
  if (s.has_triangle_elasticity() && !model_allows_inversion(s.model)) {
    for (int t = 0; t < sim.mesh.triangle_count(); ++t) {
      if (!(triangle_deformation_gradient(sim.mesh, x.data(), t).determinant() > 0.0)) {
        *message = "triangle " + std::to_string(t) + " inverted (det F <= 0)";
        return StepStatus::Inverted;
      }
    }
  }
  if (s.has_self_contact) {
    // No two boundary edges intersect (exact), hence every node-edge distance is > 0.
    StepWorkspace& ws = *sim.workspace;
    const SelfContactTimer timer{ws.contact.ms};
    if (const auto hit =
            find_self_intersection(ws.boundary, x, ws.newton.contact_grid, ws.edge_pairs)) {
      const auto& a = ws.boundary.edges[hit->edge_a];
      const auto& b = ws.boundary.edges[hit->edge_b];
      *message = "boundary edges " + std::to_string(a[0]) + "-" + std::to_string(a[1]) + " and " +
                 std::to_string(b[0]) + "-" + std::to_string(b[1]) + " intersect";
      return StepStatus::Intersected;
    }
  }
  return StepStatus::Ok;
}

}  // namespace

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

namespace {

// The boundary of every body, found once per mesh (the first step that needs it).
const Boundary& boundary_of(Simulation& sim) {
  StepWorkspace& ws = *sim.workspace;
  if (ws.boundary.edges.empty()) ws.boundary = find_boundary(sim.mesh);
  return ws.boundary;
}

// Self-contact (implicit Euler only): candidates at x^n and friction lagged there.
void fill_self_contact(Simulation& sim) {
  const SceneDef& s = sim.scene;
  StepWorkspace& ws = *sim.workspace;
  SelfContact& c = ws.problem.self_contact;
  ws.contact.ms = 0.0;
  c.on = s.has_self_contact && s.integrator == Integrator::ImplicitEuler;
  if (s.has_self_contact) boundary_of(sim);  // the invariant needs it with either integrator
  if (!c.on) return;
  c.boundary = &ws.boundary;
  c.rest = &sim.mesh.rest;
  c.params = {s.dhat, s.kappa};
  c.ccd = s.self_contact_ccd;
  c.eps_u = kFrictionEpsV * s.h;
  c.cache = &ws.contact;
  self_contact_candidates_at(c, sim.x, ws.newton.contact_grid);
  lag_self_friction(*c.boundary, *c.rest, ws.contact.pairs, sim.x, c.params, s.self_friction,
                    ws.contact.friction);
}

// The step's problem: each term the scene switches on, with its data frozen for the step.
void fill_problem(Simulation& sim) {
  const SceneDef& s = sim.scene;
  StepProblem& p = sim.workspace->problem;
  const int n = sim.mesh.node_count();
  p.mesh = &sim.mesh;
  p.mass = &sim.node_mass;
  p.h = s.h;
  p.x_start = sim.x;
  p.x_tilde = sim.x + s.h * sim.v;
  p.elasticity = {s.model, s.lame, s.projection, s.inversion_filter, s.has_triangle_elasticity()};
  p.elasticity.triangle_lame = sim.triangle_lame.empty() ? nullptr : sim.triangle_lame.data();
  p.springs.on = s.has_mass_spring;
  p.springs.stiffness = s.spring_stiffness;
  p.springs.project = s.projection != HessianProjection::None;
  p.gravity = {s.has_gravity, s.gravity};
  p.ground = ground_barrier_of(sim);
  p.friction.on = s.has_ground && s.friction > 0.0;
  p.friction.sloped = p.ground.sloped;
  p.friction.tangent = Vec2(p.ground.normal.y(), -p.ground.normal.x());
  if (p.friction.on) {
    p.friction.weight.resize(n);
    for (int i = 0; i < n; ++i)
      p.friction.weight[i] = friction_weight(
          s.friction, ground_gap(s, sim.x[2 * i], sim.x[2 * i + 1]), p.ground.at(i));
    p.friction.eps_u = kFrictionEpsV * s.h;
  }
  p.ceiling = ceiling_barrier_of(sim);
  if (p.ceiling.on) {
    p.ceiling_penalty.target = next_ceiling_nominal(s, sim.ceiling_nominal);
    // Warm start: the stiffness the last step needed (state), at least the demo's initial
    // value; restarting from the initial value let a stiff square (E = 1e8) push the
    // ceiling back up every step and spend Newton's budget re-doubling k.
    p.ceiling_penalty.stiffness =
        std::max(kCeilingInitialStiffness * sim.ceiling_mass, sim.ceiling_stiffness);
    p.ceiling_penalty.fixed = false;
  }
  p.pull = sim.pull;
  p.pull.on = sim.pull.on && sim.pull.node >= 0 && sim.pull.node < n &&
              sim.pull.target.allFinite() && sim.pull.stiffness > 0.0;
  fill_self_contact(sim);
}

// The linear solver follows the scene's [solver] settings; its symbolic analysis is redone
// only when they change (a positive definite Hessian allows PCG, see linear_solver.h).
void prepare_solver(Simulation& sim) {
  const bool positive_definite = sim.scene.projection != HessianProjection::None;
  NewtonWorkspace& ws = sim.workspace->newton;
  if (!ws.solver.ready() || ws.solver.requested() != sim.scene.linear_solver ||
      ws.solver.positive_definite() != positive_definite) {
    ws.solver.setup(ws.hessian.matrix, sim.scene.linear_solver, positive_definite);
    ws.analyzed_pattern = ws.hessian.pattern_version;
  }
}

StepReport report_of(const NewtonResult& r, int max_iterations) {
  StepReport report;
  report.status = r.status;
  report.newton_iterations = r.iterations;
  report.residual = r.residual;
  report.energy = r.energy;
  report.assembly_ms = r.assembly_ms;
  report.factor_ms = r.linear.factor_ms;
  report.solve_ms = r.linear.solve_ms;
  report.line_search_ms = r.line_search_ms;
  report.factorizations = r.linear.factorizations;
  report.pcg_iterations = r.linear.pcg_iterations;
  report.energy_evaluations = r.energy_evaluations;
  report.stopped_nodes = r.stopped_nodes;
  report.expanded_steps = r.expanded_steps;
  report.penalty_doublings = r.penalty_doublings;
  if (r.status == StepStatus::NewtonFailed)
    report.message = r.iterations >= max_iterations
                         ? "Newton reached its iteration cap (" + std::to_string(r.iterations) + ")"
                         : "no descent along the Newton direction";
  if (r.status == StepStatus::LinearSolveFailed) report.message = "the linear solve broke down";
  return report;
}

// The penalty stiffness the next step starts with. The body pushes the ceiling with
// h^2 R (R: the barrier forces at the solution); this k alone holds the ceiling within
// tol h / 2 of its target against that push. The demo's initial k (1000 times a node's
// mass) let a compressed body lift the ceiling by centimetres in the first iterations of a
// step whose ceiling could not jump to its target, and Newton then spent its budget
// doubling k back.
double next_ceiling_stiffness(const Simulation& sim, const VecX& z) {
  const StepProblem& p = sim.workspace->problem;
  const int n = sim.mesh.node_count();
  const double reaction =
      ceiling_push(z.data(), n, z[2 * n], p.ceiling.barrier, p.ceiling.node_area);
  const double h = sim.scene.h;
  return std::max(p.ceiling_penalty.stiffness, 2.0 * h * h * reaction / (sim.scene.tol * h));
}

StepReport implicit_euler_step(Simulation& sim, double& ceiling_new, double& stiffness_new) {
  fill_problem(sim);
  prepare_solver(sim);
  StepWorkspace& ws = *sim.workspace;
  const int n = sim.mesh.node_count();
  VecX& z = ws.z;
  if (z.size() != ws.problem.dof_count()) z.resize(ws.problem.dof_count());
  z.head(2 * n) = sim.x;
  if (sim.scene.has_ceiling) z[2 * n] = sim.ceiling_y;
  NewtonSettings settings;
  settings.tol = sim.scene.tol;
  settings.max_iterations = sim.scene.max_newton;
  settings.step_expansion = sim.scene.step_expansion;
  settings.friction_crossing_stop = sim.scene.friction_crossing_stop;
  // Warm start while the ceiling moves (newton.h); at rest Newton starts at x^n as in the
  // reference demo, so a body that settles within the tolerance stops as it does there.
  settings.predictor =
      sim.scene.has_ceiling && ws.problem.ceiling_penalty.target != sim.ceiling_nominal;
  const NewtonResult r = minimize_incremental_potential(ws.problem, settings, ws.newton, z);
  StepReport report = report_of(r, settings.max_iterations);
  ws.x_new = z.head(2 * n);
  ceiling_new = sim.scene.has_ceiling ? z[2 * n] : 0.0;
  stiffness_new = sim.scene.has_ceiling && r.status == StepStatus::Ok
                      ? next_ceiling_stiffness(sim, z)
                      : sim.ceiling_stiffness;
  return report;
}

// Symplectic Euler: v += h M^-1 f(x); x += h v, with f = -grad of the same per-node terms
// at the current state (the ceiling moves kinematically; friction is the same mollified
// Coulomb law on the current slip h v with the current normal force).
StepReport symplectic_euler_step(Simulation& sim, double& ceiling_new) {
  const SceneDef& s = sim.scene;
  const int n = sim.mesh.node_count();
  fill_problem(sim);
  StepWorkspace& ws = *sim.workspace;
  const StepProblem& p = ws.problem;
  StepReport report;
  ceiling_new = s.has_ceiling ? next_ceiling_nominal(s, sim.ceiling_nominal) : 0.0;
  VecX& grad = ws.newton.gradient;
  grad.setZero(2 * n);
  if (s.has_triangle_elasticity())
    add_elastic_gradient(sim.mesh, s.model, s.lame, sim.x, 1.0, grad, sim.triangle_lame);
  if (p.springs.on) add_mass_spring_gradient(p.springs, sim.x.data(), 1.0, grad.data());
  VecX& v_new = ws.v_new;
  v_new = sim.v;
  for (int i = 0; i < n; ++i) {
    const double x = sim.x[2 * i], y = sim.x[2 * i + 1];
    const NodeState node{i, x, y, sim.node_mass[i], x, sim.ceiling_y};
    NodeDerivatives d;
    d.gx = grad[2 * i];
    d.gy = grad[2 * i + 1];
    for_each_node_term(p, [&](const auto& term) {
      if (!term.on) return;
      if constexpr (std::is_same_v<std::decay_t<decltype(term)>, GroundFriction>) {
        const double gap = p.ground.gap(x, y);
        if (gap < p.ground.barrier.dhat) {
          const Vec2 t = term.tangent;
          const double slip =
              term.sloped ? s.h * t.dot(sim.v.segment<2>(2 * i)) : s.h * sim.v[2 * i];
          const double f = friction_derivative(
              slip, friction_weight(s.friction, gap, p.ground.at(i)), term.eps_u);
          d.gx += term.sloped ? f * t.x() : f;
          if (term.sloped) d.gy += f * t.y();
        }
      } else {
        term.add_derivatives(node, 1.0, d);
      }
    });
    if (p.pull.on && p.pull.node == i)
      p.pull.add_derivatives(sim.x.segment<2>(2 * i), 1.0, d.gx, d.gy, d.hxx, d.hyy);
    v_new.segment<2>(2 * i) += s.h / sim.node_mass[i] * Vec2(-d.gx, -d.gy);
  }
  for (int dof : p.fixed.dofs) v_new[dof] = 0.0;
  ws.x_new = sim.x + s.h * v_new;
  report.energy = total_energy(sim);
  return report;
}

}  // namespace

Simulation make_simulation(const SceneDef& scene) {
  Simulation sim;
  sim.scene = scene;
  sim.mesh = scene_mesh(scene);
  sim.node_mass = scene_node_masses(scene, sim.mesh);
  sim.node_contact_area = scene_node_contact_areas(scene, sim.mesh);
  sim.triangle_lame = scene_triangle_lame(scene, sim.mesh);
  double total = 0.0;
  for (double m : sim.node_mass) total += m;
  sim.ceiling_mass = total / sim.mesh.node_count();
  sim.x = initial_positions(scene, sim.mesh);
  sim.v = initial_velocities(scene, sim.mesh);
  sim.ceiling_y = sim.ceiling_nominal = scene.ceiling_y;
  sim.workspace = std::make_unique<StepWorkspace>();
  NewtonWorkspace& ws = sim.workspace->newton;
  StepWorkspace& step_ws = *sim.workspace;
  if (scene.has_mass_spring) step_ws.springs = mesh_springs(sim.mesh);
  ws.hessian =
      build_sparse_hessian(sim.mesh, scene.has_ceiling, spring_node_pairs(step_ws.springs));
  if (scene.has_mass_spring) {
    step_ws.spring_slots = spring_slots(step_ws.springs, ws.hessian);
    step_ws.problem.springs.springs = &step_ws.springs;
    step_ws.problem.springs.slots = &step_ws.spring_slots;
  }
  const std::vector<int> fixed = select_fixed_nodes(scene, sim.mesh);
  step_ws.problem.fixed = make_fixed_dofs(fixed, ws.hessian);
  for (int node : fixed) sim.v.segment<2>(2 * node).setZero();
  ws.min_node_mass = *std::min_element(sim.node_mass.begin(), sim.node_mass.end());
  if (scene.integrator == Integrator::ImplicitEuler) prepare_solver(sim);
  const int dofs = 2 * sim.mesh.node_count();
  sim.workspace->z.resize(dofs + (scene.has_ceiling ? 1 : 0));
  sim.workspace->x_new.resize(dofs);
  sim.workspace->v_new.resize(dofs);
  return sim;
}

namespace {
// A body's own material changes no mesh (update_scene refreshes triangle_lame).
bool same_bodies_but_material(const std::vector<BodyDef>& a, const std::vector<BodyDef>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (a[k].side != b[k].side || a[k].n_seg != b[k].n_seg || a[k].offset != b[k].offset ||
        a[k].velocity != b[k].velocity)
      return false;
  return true;
}
}  // namespace

bool needs_new_mesh(const SceneDef& old, const SceneDef& next) {
  return old.side != next.side || old.n_seg != next.n_seg || old.density != next.density ||
         old.mass != next.mass || old.jitter != next.jitter || old.seed != next.seed ||
         old.has_ceiling != next.has_ceiling || old.has_mass_spring != next.has_mass_spring ||
         old.has_fixed != next.has_fixed || old.fixed_corners != next.fixed_corners ||
         old.fixed_box_min != next.fixed_box_min || old.fixed_box_max != next.fixed_box_max ||
         !same_bodies_but_material(old.bodies, next.bodies);
}

void update_scene(Simulation& sim, const SceneDef& scene) {
  if (needs_new_mesh(sim.scene, scene)) {
    sim = make_simulation(scene);
    return;
  }
  sim.scene = scene;
  sim.triangle_lame = scene_triangle_lame(scene, sim.mesh);
}

StepReport step(Simulation& sim) {
  const auto start = std::chrono::steady_clock::now();
  StepWorkspace& ws = *sim.workspace;
  double ceiling_new = 0.0, stiffness_new = sim.ceiling_stiffness;
  StepReport report;
  if (sim.scene.integrator == Integrator::SymplecticEuler) {
    report = symplectic_euler_step(sim, ceiling_new);
  } else {
    report = implicit_euler_step(sim, ceiling_new, stiffness_new);
    ws.v_new = (ws.x_new - sim.x) / sim.scene.h;
  }
  if (report.status == StepStatus::Ok)
    report.status = check_invariants(sim, ws.x_new, ws.v_new, ceiling_new, &report.message);
  if (report.status == StepStatus::Ok) {
    sim.x.swap(ws.x_new);
    sim.v.swap(ws.v_new);
    if (sim.scene.has_ceiling) {
      sim.ceiling_y = ceiling_new;
      sim.ceiling_nominal = next_ceiling_nominal(sim.scene, sim.ceiling_nominal);
      sim.ceiling_stiffness = stiffness_new;
    }
    sim.time += sim.scene.h;
    ++sim.step_count;
  }
  if (sim.scene.has_self_contact) report.self_contact_ms = ws.contact.ms;
  report.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return report;
}

std::vector<double> triangle_det_f(const Simulation& sim) {
  std::vector<double> det(sim.mesh.triangle_count());
  for (int t = 0; t < sim.mesh.triangle_count(); ++t)
    det[t] = triangle_deformation_gradient(sim.mesh, sim.x.data(), t).determinant();
  return det;
}

double min_plane_gap(const Simulation& sim) {
  double gap = std::numeric_limits<double>::infinity();
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    const double y = sim.x[2 * i + 1];
    if (sim.scene.has_ground) gap = std::min(gap, ground_gap(sim.scene, sim.x[2 * i], y));
    if (sim.scene.has_ceiling) gap = std::min(gap, sim.ceiling_y - y);
  }
  return gap;
}

double min_self_gap(const Simulation& sim) {
  if (!sim.scene.has_self_contact || !sim.workspace) return INFINITY;
  Boundary scratch;
  const Boundary& boundary = boundary_now(sim, scratch);
  std::vector<PointEdgePair> pairs;
  BroadPhaseGrid grid;
  point_edge_candidates(boundary, sim.x, sim.scene.dhat, grid, pairs);
  const double gap = min_self_gap(boundary, pairs, sim.x);
  return gap < sim.scene.dhat ? gap : INFINITY;
}

double total_energy(const Simulation& sim) {
  const SceneDef& s = sim.scene;
  const Gravity gravity{s.has_gravity, s.gravity};
  double e = s.has_triangle_elasticity()
                 ? elastic_energy(sim.mesh, s.model, s.lame, sim.x, sim.triangle_lame)
                 : 0.0;
  if (s.has_mass_spring) {
    const MassSpring springs{true, s.spring_stiffness, true, &sim.workspace->springs, nullptr};
    e += mass_spring_energy(springs, sim.x.data());
  }
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    const NodeState node{i, sim.x[2 * i], sim.x[2 * i + 1], sim.node_mass[i], 0.0, 0.0};
    e += 0.5 * sim.node_mass[i] * sim.v.segment<2>(2 * i).squaredNorm();
    if (gravity.on) e += gravity.value(node);
  }
  return e;
}

const char* linear_solver_backend(const Simulation& sim) {
  return sim.workspace ? sim.workspace->newton.solver.backend_name() : "";
}

}  // namespace invfree
