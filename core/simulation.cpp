#include "simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "material/triangle_elasticity.h"
#include "scene/initial_state.h"

namespace invfree {

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
    if ((s.has_ground && !(y > s.ground_y)) || (s.has_ceiling && !(y < ceiling))) {
      *message = "node " + std::to_string(i) + " reached or crossed a plane";
      return StepStatus::Penetrated;
    }
  }
  if (!model_allows_inversion(s.model)) {
    for (int t = 0; t < sim.mesh.triangle_count(); ++t) {
      const auto& tri = sim.mesh.triangles[t];
      const Mat2 F = deformation_gradient(x.segment<2>(2 * tri[0]), x.segment<2>(2 * tri[1]),
                                          x.segment<2>(2 * tri[2]), sim.mesh.rest_shape_inverse[t]);
      if (!(F.determinant() > 0.0)) {
        *message = "triangle " + std::to_string(t) + " inverted (det F <= 0)";
        return StepStatus::Inverted;
      }
    }
  }
  return StepStatus::Ok;
}

void fill_problem(Simulation& sim) {
  const SceneDef& s = sim.scene;
  StepProblem& p = sim.problem;
  const int n = sim.mesh.node_count();
  p.mesh = &sim.mesh;
  p.mass = &sim.node_mass;
  p.model = s.model;
  p.lame = s.lame;
  p.projection = s.projection;
  p.h = s.h;
  p.x_start = sim.x;
  p.x_tilde = sim.x + s.h * sim.v;
  p.gravity_on = s.has_gravity;
  p.gravity = s.gravity;
  p.barrier = barrier_params(s);
  p.ground_on = s.has_ground;
  p.ground_y = s.ground_y;
  p.friction_on = s.has_ground && s.friction > 0.0;
  if (p.friction_on) {
    p.friction_weight.assign(n, 0.0);
    for (int i = 0; i < n; ++i) {
      const double d = sim.x[2 * i + 1] - s.ground_y;
      if (d < s.dhat) p.friction_weight[i] = -s.friction * barrier_derivative(d, p.barrier);
    }
    p.friction_eps_u = kFrictionEpsV * s.h;
  }
  p.ceiling_on = s.has_ceiling;
  if (p.ceiling_on) {
    p.ceiling_target = next_ceiling_nominal(s, sim.ceiling_nominal);
    // Warm start: keep the stiffness the last step needed. Restarting from the demo's
    // initial value let a stiff square (E = 1e8) push the ceiling back up every step and
    // spend Newton's whole iteration budget re-doubling k.
    p.ceiling_stiffness =
        std::max(kCeilingInitialStiffness * sim.ceiling_mass, p.ceiling_stiffness);
    p.ceiling_fixed = false;
  }
  p.pull_on = sim.pull.on && sim.pull.node >= 0 && sim.pull.node < n &&
              sim.pull.target.allFinite() && sim.pull.stiffness > 0.0;
  p.pull_node = sim.pull.node;
  p.pull_target = sim.pull.target;
  p.pull_stiffness = sim.pull.stiffness;
}

// The linear solver follows the scene's [solver] settings; its symbolic analysis is redone
// only when they change (a positive definite Hessian allows PCG, see linear_solver.h).
void prepare_solver(Simulation& sim) {
  const bool positive_definite = sim.scene.projection != HessianProjection::None;
  LinearSolver& solver = sim.workspace.solver;
  if (!solver.ready() || solver.requested() != sim.scene.linear_solver ||
      solver.positive_definite() != positive_definite)
    solver.setup(sim.workspace.hessian.matrix, sim.scene.linear_solver, positive_definite);
}

StepReport implicit_euler_step(Simulation& sim, double& ceiling_new) {
  fill_problem(sim);
  prepare_solver(sim);
  const int n = sim.mesh.node_count();
  VecX& z = sim.z;
  if (z.size() != sim.problem.dof_count()) z.resize(sim.problem.dof_count());
  z.head(2 * n) = sim.x;
  if (sim.scene.has_ceiling) z[2 * n] = sim.ceiling_y;
  NewtonSettings settings;
  settings.tol = sim.scene.tol;
  settings.max_iterations = sim.scene.max_newton;
  settings.inversion_filter = sim.scene.inversion_filter;
  settings.step_expansion = sim.scene.step_expansion;
  settings.friction_crossing_stop = sim.scene.friction_crossing_stop;
  // Warm start while the ceiling moves (newton.h); at rest Newton starts at x^n as in the
  // reference demo, so a body that settles within the tolerance stops as it does there.
  settings.predictor = sim.scene.has_ceiling && sim.problem.ceiling_target != sim.ceiling_nominal;
  const NewtonResult r = minimize_incremental_potential(sim.problem, settings, sim.workspace, z);
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
    report.message = r.iterations >= settings.max_iterations
                         ? "Newton reached its iteration cap (" + std::to_string(r.iterations) + ")"
                         : "no descent along the Newton direction";
  if (r.status == StepStatus::LinearSolveFailed) report.message = "the linear solve broke down";
  sim.x_new = z.head(2 * n);
  ceiling_new = sim.scene.has_ceiling ? z[2 * n] : 0.0;
  if (sim.scene.has_ceiling && r.status == StepStatus::Ok) {
    // The body pushes the ceiling with h^2 R (R: the barrier forces at the solution). The
    // next step starts with a penalty that alone would hold the ceiling within tol h / 2
    // of its target against that push. The demo's initial k (1000 times a node's mass)
    // let a compressed body lift the ceiling by centimetres in the first iterations of a
    // step whose ceiling could not jump to its target, and Newton then spent its budget
    // doubling k back (n_seg 256: k 15 -> 969 in one step, then the cap of 100).
    const double reaction = ceiling_push(z.data(), n, z[2 * n], sim.problem.barrier);
    const double h = sim.scene.h;
    sim.problem.ceiling_stiffness =
        std::max(sim.problem.ceiling_stiffness, 2.0 * h * h * reaction / (sim.scene.tol * h));
  }
  return report;
}

// Symplectic Euler: v += h M^-1 f(x); x += h v, with the same energies (the ceiling moves
// kinematically, friction is the same mollified Coulomb law on the current velocity).
StepReport symplectic_euler_step(Simulation& sim, double& ceiling_new) {
  const SceneDef& s = sim.scene;
  const int n = sim.mesh.node_count();
  const BarrierParams b = barrier_params(s);
  StepReport report;
  ceiling_new = s.has_ceiling ? next_ceiling_nominal(s, sim.ceiling_nominal) : 0.0;
  VecX& grad = sim.workspace.gradient;
  grad.setZero(2 * n);
  add_elastic_gradient(sim.mesh, s.model, s.lame, sim.x, 1.0, grad);
  VecX& v_new = sim.v_new;
  v_new = sim.v;
  for (int i = 0; i < n; ++i) {
    Vec2 f = -grad.segment<2>(2 * i);
    if (s.has_gravity) f += sim.node_mass[i] * s.gravity;
    const double y = sim.x[2 * i + 1];
    if (s.has_ground) {
      const double d = y - s.ground_y;
      const double db = barrier_derivative(d, b);
      f.y() -= db;
      if (s.friction > 0.0 && d < s.dhat)
        f.x() -= friction_derivative(s.h * sim.v[2 * i], -s.friction * db, kFrictionEpsV * s.h);
    }
    if (s.has_ceiling) f.y() += barrier_derivative(sim.ceiling_y - y, b);
    if (sim.pull.on && sim.pull.node == i)
      f -= sim.pull.stiffness * (sim.x.segment<2>(2 * i) - sim.pull.target);
    v_new.segment<2>(2 * i) += s.h / sim.node_mass[i] * f;
  }
  sim.x_new = sim.x + s.h * v_new;
  report.energy = total_energy(sim);
  return report;
}

}  // namespace

Simulation make_simulation(const SceneDef& scene) {
  Simulation sim;
  sim.scene = scene;
  sim.mesh = square_mesh(scene.side, scene.n_seg);
  sim.node_mass = node_masses(sim.mesh, scene.density, scene.mass);
  double total = 0.0;
  for (double m : sim.node_mass) total += m;
  sim.ceiling_mass = total / sim.mesh.node_count();
  sim.x = initial_positions(scene, sim.mesh);
  sim.v = scene.initial_velocity.replicate(sim.mesh.node_count(), 1);
  sim.ceiling_y = sim.ceiling_nominal = scene.ceiling_y;
  sim.workspace.hessian = build_sparse_hessian(sim.mesh, scene.has_ceiling);
  sim.workspace.min_node_mass = *std::min_element(sim.node_mass.begin(), sim.node_mass.end());
  if (scene.integrator == Integrator::ImplicitEuler) prepare_solver(sim);
  const int dofs = 2 * sim.mesh.node_count();
  sim.z.resize(dofs + (scene.has_ceiling ? 1 : 0));
  sim.x_new.resize(dofs);
  sim.v_new.resize(dofs);
  return sim;
}

void update_scene(Simulation& sim, const SceneDef& scene) {
  const SceneDef& old = sim.scene;
  const bool new_mesh = old.side != scene.side || old.n_seg != scene.n_seg ||
                        old.density != scene.density || old.mass != scene.mass ||
                        old.jitter != scene.jitter || old.seed != scene.seed ||
                        old.has_ceiling != scene.has_ceiling;
  if (new_mesh) {
    sim = make_simulation(scene);
    return;
  }
  sim.scene = scene;
}

StepReport step(Simulation& sim) {
  const auto start = std::chrono::steady_clock::now();
  double ceiling_new = 0.0;
  StepReport report;
  if (sim.scene.integrator == Integrator::SymplecticEuler) {
    report = symplectic_euler_step(sim, ceiling_new);
  } else {
    report = implicit_euler_step(sim, ceiling_new);
    sim.v_new = (sim.x_new - sim.x) / sim.scene.h;
  }
  if (report.status == StepStatus::Ok)
    report.status = check_invariants(sim, sim.x_new, sim.v_new, ceiling_new, &report.message);
  if (report.status == StepStatus::Ok) {
    sim.x.swap(sim.x_new);
    sim.v.swap(sim.v_new);
    if (sim.scene.has_ceiling) {
      sim.ceiling_y = ceiling_new;
      sim.ceiling_nominal = next_ceiling_nominal(sim.scene, sim.ceiling_nominal);
    }
    sim.time += sim.scene.h;
    ++sim.step_count;
  }
  report.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return report;
}

std::vector<double> triangle_det_f(const Simulation& sim) {
  std::vector<double> det(sim.mesh.triangle_count());
  for (int t = 0; t < sim.mesh.triangle_count(); ++t) {
    const auto& tri = sim.mesh.triangles[t];
    det[t] = deformation_gradient(sim.x.segment<2>(2 * tri[0]), sim.x.segment<2>(2 * tri[1]),
                                  sim.x.segment<2>(2 * tri[2]), sim.mesh.rest_shape_inverse[t])
                 .determinant();
  }
  return det;
}

double min_plane_gap(const Simulation& sim) {
  double gap = std::numeric_limits<double>::infinity();
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    const double y = sim.x[2 * i + 1];
    if (sim.scene.has_ground) gap = std::min(gap, y - sim.scene.ground_y);
    if (sim.scene.has_ceiling) gap = std::min(gap, sim.ceiling_y - y);
  }
  return gap;
}

double total_energy(const Simulation& sim) {
  const SceneDef& s = sim.scene;
  double e = elastic_energy(sim.mesh, s.model, s.lame, sim.x);
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    e += 0.5 * sim.node_mass[i] * sim.v.segment<2>(2 * i).squaredNorm();
    if (s.has_gravity) e -= sim.node_mass[i] * s.gravity.dot(sim.x.segment<2>(2 * i));
  }
  return e;
}

}  // namespace invfree
