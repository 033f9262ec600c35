#include "simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <type_traits>

#include "collision/intersection_check.h"
#include "energy_report.h"
#include "linalg/blocked_vector_ops.h"
#include "make_terms.h"
#include "potential/first_failing_triangle.h"
#include "potential/term_sums.h"
#include "potential/work_blocks.h"
#include "scene/fixed_nodes.h"
#include "scene/initial_state.h"
#include "scene/reduced_basis.h"
#include "scene/scene_mesh.h"
#include "solver/step_workspace.h"

namespace invfree {

Simulation::Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;
Simulation::~Simulation() = default;

namespace {

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
    const int t = first_failing_triangle(sim.mesh, x.data(), [](double det) { return det > 0.0; });
    if (t >= 0) {
      *message = "triangle " + std::to_string(t) + " inverted (det F <= 0)";
      return StepStatus::Inverted;
    }
  }
  if (s.self_contact_on()) {
    // No two boundary edges intersect (exact), hence every node-edge distance is > 0. The
    // clearance certificate proves it without the check while nothing came close since
    // the state it measured; once it only proves it pair by pair, this state is measured
    // anew (intersection-free by that proof), so that the next steps take the quick path;
    // otherwise the exact check runs, and then the measurement.
    StepWorkspace& ws = *sim.workspace;
    SelfContactCache& cache = ws.caches.contact;
    const SelfContactTimer timer{cache.ms};
    const double m = clearance_motion(ws.boundary, cache.clearance, x, nullptr, 0.0);
    if (is_clear(cache.clearance, s.dhat, m)) return StepStatus::Ok;
    if (near_pairs(ws.boundary, cache.clearance, s.dhat, m, cache.near) && cache.near.empty()) {
      measure_clearance(ws.boundary, sim.mesh.rest, x, {s.dhat, s.kappa}, ws.caches.grid,
                        cache.clearance);
      return StepStatus::Ok;
    }
    if (const auto hit = find_self_intersection(ws.boundary, x, ws.caches.grid, ws.edge_pairs)) {
      const auto& a = ws.boundary.edges[hit->edge_a];
      const auto& b = ws.boundary.edges[hit->edge_b];
      *message = "boundary edges " + std::to_string(a[0]) + "-" + std::to_string(a[1]) + " and " +
                 std::to_string(b[0]) + "-" + std::to_string(b[1]) + " intersect";
      return StepStatus::Intersected;
    }
    measure_clearance(ws.boundary, sim.mesh.rest, x, {s.dhat, s.kappa}, ws.caches.grid,
                      cache.clearance);
  }
  return StepStatus::Ok;
}

// What a step reports about the state it accepted, each a number or the step fails
// (check_reported_quantities): finite positions can still overflow a product of them, a
// kinetic energy of m v^2 at v = 1e200 m/s, springs' energy at a huge stiffness, or det F.
struct ReportedState {
  double kinetic = 0.0, elastic = 0.0, gravitational = 0.0, contact = 0.0;
};

// v = (x_new - x) / h over the pool's fixed blocks (each entry as the plain expression).
void blocked_velocity(const VecX& x_new, const VecX& x, double h, VecX& v) {
  v.resize(x.size());
  for_each_block(x.size(), [&](int begin, int length, int) {
    v.segment(begin, length) = (x_new.segment(begin, length) - x.segment(begin, length)) / h;
  });
}

// The accepted state's energies as energy_report_of adds them, from the step's own terms
// (no allocation), except self-contact's barrier: its candidates need a broad phase, and
// check_invariants has just proved every node-edge distance positive, where it is finite.
ReportedState reported_energies(const Simulation& sim, const VecX& z, const VecX& v) {
  StepWorkspace& ws = *sim.workspace;
  const StepProblem& p = ws.problem;
  ReportedState r;
  auto reported = [](EnergyKind k) {
    return k == EnergyKind::Elastic || k == EnergyKind::Gravity || k == EnergyKind::Contact;
  };
  // The node sums in fixed blocks (work_blocks.h), added in block order: the same bits on
  // any thread count, and no serial pass over every node in a step.
  const int n = p.node_count();
  const BlockSplit blocks = split_blocks(n, kNodeBlock, kMaxBlocks);
  double kinetic[kMaxBlocks];
  EnergyBins block_bins[kMaxBlocks];
  run_blocks(blocks.blocks, [&](int b) {
    double k = 0.0;
    EnergyBins e;
    for (int i = blocks.begin(b); i < blocks.end(b, n); ++i) {
      k += 0.5 * (*p.mass)[i] * v.segment<2>(2 * i).squaredNorm();
      const NodeState s = p.node_state(z.data(), i);
      p.for_each_node_term([&](const auto& term) {
        if (term.on && reported(term.kind)) e[term.kind] += term.value(s);
      });
    }
    kinetic[b] = k;
    block_bins[b] = e;
  });
  EnergyBins bins;
  for (int b = 0; b < blocks.blocks; ++b) {
    r.kinetic += kinetic[b];
    for (std::size_t k = 0; k < bins.value.size(); ++k) bins.value[k] += block_bins[b].value[k];
  }
  const TermPoint at = term_point(p, ws.caches, z);
  p.for_each_mesh_term([&](const auto& term) {
    using T = std::decay_t<decltype(term)>;
    if constexpr (!HasBegin<T>)
      if (term.on && reported(T::kind)) bins[T::kind] += term.value(at, 1.0);
  });
  r.elastic = bins[EnergyKind::Elastic];
  r.gravitational = bins[EnergyKind::Gravity];
  r.contact = bins[EnergyKind::Contact];
  return r;
}

// Every quantity the step reports (simulate's CSV and summary, render's and live's labels)
// is a number: the energies of the accepted state, every triangle's det F, the step's own
// energy and residual. Otherwise NonFinite, naming the first that is not.
StepStatus check_reported_quantities(const Simulation& sim, const ReportedState& e,
                                     const StepReport& report, const VecX& x,
                                     std::string* message) {
  auto fail = [&](const std::string& what, double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    *message = what + " is not finite (" + text + ")";
    return StepStatus::NonFinite;
  };
  if (!std::isfinite(e.kinetic)) return fail("the kinetic energy", e.kinetic);
  if (!std::isfinite(e.elastic)) return fail("the elastic energy", e.elastic);
  if (!std::isfinite(e.gravitational)) return fail("the gravitational energy", e.gravitational);
  if (!std::isfinite(e.contact)) return fail("the contact energy", e.contact);
  if (!std::isfinite(report.energy)) return fail("the step's energy", report.energy);
  if (!std::isfinite(report.residual)) return fail("the Newton residual", report.residual);
  if (const int t =
          first_failing_triangle(sim.mesh, x.data(), [](double det) { return std::isfinite(det); });
      t >= 0)
    return fail("det F of triangle " + std::to_string(t),
                triangle_deformation_gradient(sim.mesh, x.data(), t).determinant());
  return StepStatus::Ok;
}

// The boundary of every body, found once per mesh (the first step that needs it).
const Boundary& boundary_of(Simulation& sim) {
  StepWorkspace& ws = *sim.workspace;
  if (ws.boundary.edges.empty()) {
    ws.boundary = find_boundary(sim.mesh);
    if (sim.scene.self_contact_on()) {
      reserve_self_contact(ws.boundary, ws.caches.contact, ws.caches.grid);
      ws.edge_pairs.reserve(8 * ws.boundary.edges.size());
      ws.caches.scratch.resize(ws.z.size());  // path_step's direction
    }
  }
  return ws.boundary;
}

// The step's terms; self-contact (implicit Euler only) needs the bodies' boundary, which
// the invariant check needs with either integrator.
void fill_problem(Simulation& sim) {
  StepWorkspace& ws = *sim.workspace;
  const SceneDef& s = sim.scene;
  const Boundary* boundary = s.self_contact_on() ? &boundary_of(sim) : nullptr;
  if (s.integrator == Integrator::SymplecticEuler) boundary = nullptr;
  make_terms(sim, boundary, ws.problem, ws.caches);
}

NewtonSettings newton_settings(const SceneDef& s) {
  NewtonSettings settings;
  settings.tol = s.tol;
  settings.max_iterations = s.max_newton;
  settings.step_expansion = s.step_expansion;
  settings.friction_crossing_stop = s.friction_crossing_stop;
  settings.linear_solver = s.linear_solver;
  // Without inertia the Hessian has no lower bound for PCG's error estimate: a static
  // step factorises directly (find_scene_problem refuses "pcg" with "static").
  if (s.is_static() && s.linear_solver == LinearSolverKind::Auto)
    settings.linear_solver = LinearSolverKind::Ldlt;
  settings.projected = s.projection != HessianProjection::None;
  return settings;
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
  const double reaction = p.ceiling.push(z.data(), n, z[2 * n]);
  const double h = sim.scene.h;
  return std::max(p.ceiling_penalty.stiffness, 2.0 * h * h * reaction / (sim.scene.tol * h));
}

StepReport implicit_euler_step(Simulation& sim, double& ceiling_new, double& stiffness_new) {
  fill_problem(sim);
  StepWorkspace& ws = *sim.workspace;
  const int n = sim.mesh.node_count();
  VecX& z = ws.z;
  if (z.size() != ws.problem.dof_count()) z.resize(ws.problem.dof_count());
  z.head(2 * n) = sim.x;
  if (sim.scene.has_ceiling) z[2 * n] = sim.ceiling_y;
  NewtonSettings settings = newton_settings(sim.scene);
  // Warm start while the ceiling moves (newton.h); at rest Newton starts at x^n as in the
  // reference demo, so a body that settles within the tolerance stops as it does there.
  settings.predictor =
      sim.scene.has_ceiling && ws.problem.ceiling_penalty.target != sim.ceiling_nominal;
  const NewtonResult r =
      minimize_incremental_potential(ws.problem, ws.caches, settings, ws.newton, z);
  StepReport report = report_of(r, settings.max_iterations);
  ws.x_new = z.head(2 * n);
  ceiling_new = sim.scene.has_ceiling ? z[2 * n] : 0.0;
  stiffness_new = sim.scene.has_ceiling && r.status == StepStatus::Ok
                      ? next_ceiling_stiffness(sim, z)
                      : sim.ceiling_stiffness;
  return report;
}

// Symplectic Euler: v += h M^-1 f(x); x += h v, with f = -grad of the same terms at the
// current state (term_sums.h's explicit_gradient; the ceiling moves kinematically;
// friction is the same mollified Coulomb law on the current slip h v with the current
// normal force).
StepReport symplectic_euler_step(Simulation& sim, double& ceiling_new) {
  const SceneDef& s = sim.scene;
  const int n = sim.mesh.node_count();
  fill_problem(sim);
  StepWorkspace& ws = *sim.workspace;
  StepReport report;
  ceiling_new = s.has_ceiling ? next_ceiling_nominal(s, sim.ceiling_nominal) : 0.0;
  VecX& grad = ws.newton.gradient;
  explicit_gradient(ws.problem, ws.caches, sim.x, sim.v, sim.ceiling_y, grad);
  VecX& v_new = ws.v_new;
  v_new = sim.v;
  for (int i = 0; i < n; ++i)
    v_new.segment<2>(2 * i) += s.h / sim.node_mass[i] * Vec2(-grad[2 * i], -grad[2 * i + 1]);
  for (int dof : ws.problem.fixed.dofs) v_new[dof] = 0.0;
  ws.x_new = sim.x + s.h * v_new;
  // report.energy, the accepted state's kinetic + elastic + gravitational energy, is set
  // by step() with the check of every reported quantity.
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
  if (scene.has_mass_spring) {
    step_ws.springs =
        scene.springs.empty() ? mesh_springs(sim.mesh) : listed_springs(sim.mesh, scene.springs);
    step_ws.spring_count = spring_counts(step_ws.springs, sim.mesh.node_count());
  }
  ws.hessian =
      build_sparse_hessian(sim.mesh, scene.has_ceiling, spring_node_pairs(step_ws.springs));
  if (scene.has_mass_spring) {
    step_ws.spring_slots = spring_slots(step_ws.springs, ws.hessian);
    step_ws.problem.springs.springs = &step_ws.springs;
    step_ws.problem.springs.slots = &step_ws.spring_slots;
  }
  const std::vector<int> fixed = select_fixed_dofs(scene, sim.mesh);
  step_ws.problem.fixed = make_fixed_dofs(fixed, ws.hessian);
  for (int dof : fixed) sim.v[dof] = 0.0;
  if (scene.is_static()) sim.v.setZero();
  if (scene.has_tractions()) {
    const Boundary& boundary = boundary_of(sim);
    sim.node_load = traction_node_forces(scene, sim.mesh, boundary);
    sim.pressure_edges = pressure_edges(scene, sim.mesh, boundary);
  }
  ws.min_node_mass = *std::min_element(sim.node_mass.begin(), sim.node_mass.end());
  ws.reduced.basis = build_reduced_basis(scene, sim.mesh).basis;  // empty: full space
  if (scene.integrator != Integrator::SymplecticEuler && !ws.reduced.on())
    prepare_linear_solver(ws, newton_settings(scene).linear_solver,
                          scene.projection != HessianProjection::None);
  const int dofs = 2 * sim.mesh.node_count();
  sim.workspace->z.resize(dofs + (scene.has_ceiling ? 1 : 0));
  sim.workspace->x_new.resize(dofs);
  sim.workspace->v_new.resize(dofs);
  return sim;
}

// The fields marked "needs a new mesh" in the scene field table (scene/scene_fields.h); a
// body's own material is not one (update_scene refreshes triangle_lame).
bool needs_new_mesh(const SceneDef& old, const SceneDef& next) {
  return fields_need_new_mesh(old, next);
}

void update_scene(Simulation& sim, const SceneDef& scene) {
  if (needs_new_mesh(sim.scene, scene)) {
    sim = make_simulation(scene);
    return;
  }
  // The modal basis is the rest Hessian's: a new material (the live sliders) has new modes.
  const bool new_modes = scene.reduced_basis == ReducedBasis::Modal &&
                         (scene.model != sim.scene.model || scene.lame != sim.scene.lame ||
                          scene.bodies != sim.scene.bodies);
  sim.scene = scene;
  sim.triangle_lame = scene_triangle_lame(scene, sim.mesh);
  if (new_modes) {
    ReducedSolve& reduced = sim.workspace->newton.reduced;
    reduced.basis = build_reduced_basis(scene, sim.mesh).basis;
    reduced.transposed.resize(0, 0);
  }
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
    if (sim.scene.is_static())
      ws.v_new.setZero();  // equilibrium: nothing moves between load steps
    else
      blocked_velocity(ws.x_new, sim.x, sim.scene.h, ws.v_new);
  }
  if (report.status == StepStatus::Ok)
    report.status = check_invariants(sim, ws.x_new, ws.v_new, ceiling_new, &report.message);
  if (report.status == StepStatus::Ok) {
    // The accepted state as z = [x; c] for its energies.
    const int n = sim.mesh.node_count();
    VecX& z = ws.z;
    z.head(2 * n) = ws.x_new;
    if (sim.scene.has_ceiling) z[2 * n] = ceiling_new;
    const ReportedState e = reported_energies(sim, z, ws.v_new);
    // Symplectic Euler has no incremental potential: its energy is the accepted state's
    // kinetic + elastic + gravitational energy.
    if (sim.scene.integrator == Integrator::SymplecticEuler)
      report.energy = e.kinetic + e.elastic + e.gravitational;
    report.status = check_reported_quantities(sim, e, report, ws.x_new, &report.message);
  }
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
  if (sim.scene.self_contact_on()) report.self_contact_ms = ws.caches.contact.ms;
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
  if (!sim.scene.self_contact_on() || !sim.workspace) return INFINITY;
  Boundary scratch;
  const Boundary& boundary = boundary_now(sim, scratch);
  std::vector<PointEdgePair> pairs;
  BroadPhaseGrid grid;
  point_edge_candidates(boundary, sim.x, sim.scene.dhat, grid, pairs);
  const double gap = min_self_gap(boundary, pairs, sim.x);
  return gap < sim.scene.dhat ? gap : INFINITY;
}

double total_energy(const Simulation& sim) {
  const EnergyReport e = energy_report(sim, EnergyReportParts::WithoutContact);
  return e.kinetic + e.elastic + e.gravitational;
}

const char* linear_solver_backend(const Simulation& sim) {
  return sim.workspace ? sim.workspace->newton.solver.backend_name() : "";
}

}  // namespace invfree
