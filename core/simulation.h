// A running simulation: the scene, its mesh, the state (positions, velocities, ceiling,
// time) and the solver's reusable workspace. `step` advances one time step by implicit
// Euler (projected Newton on the incremental potential) or symplectic Euler, checks the
// invariants, and leaves the state untouched when the step fails.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"
#include "solver/newton.h"

namespace invfree {

struct StepReport {
  StepStatus status = StepStatus::Ok;
  int newton_iterations = 0;
  double residual = 0.0;
  double energy = 0.0;   // incremental potential at the accepted state
  double wall_ms = 0.0;  // time spent in the step
  std::string message;   // empty when ok
  // Where the step's time went (ms, steady clock; the rest of wall_ms is the warm start,
  // the invariant checks and bookkeeping): gradient + Hessian assembly, numeric
  // factorisations, solves (triangular solves and PCG iterations), line search (filters
  // and energy evaluations).
  double assembly_ms = 0.0;
  double factor_ms = 0.0;
  double solve_ms = 0.0;
  double line_search_ms = 0.0;
  int factorizations = 0;
  int pcg_iterations = 0;
  int energy_evaluations = 0;
  int stopped_nodes = 0;  // Newton's safeguards at work (core/newton.h)
  int expanded_steps = 0;
  int penalty_doublings = 0;  // the ceiling's penalty doubled (converged short of the target)
};

// A spring pulling one node toward a target (the live window's grab), on while dragging.
struct PullSpring {
  bool on = false;
  int node = 0;
  Vec2 target = Vec2::Zero();
  double stiffness = 0.0;  // N/m
};

struct Simulation {
  SceneDef scene;
  Mesh mesh;
  std::vector<double> node_mass;
  double ceiling_mass = 0.0;
  // State.
  VecX x, v;               // 2N each
  double ceiling_y = 0.0;  // actual height (within tol * h of ceiling_nominal)
  double ceiling_nominal = 0.0;
  double time = 0.0;
  long step_count = 0;
  PullSpring pull;  // input: applied by every step while on
  // Solver workspace (sparsity pattern and symbolic factorisation, built once per mesh)
  // and the step's scratch vectors: a step allocates nothing.
  NewtonWorkspace workspace;
  StepProblem problem;
  VecX z, x_new, v_new;
};

// Builds a simulation from a validated scene (see validate_scene).
Simulation make_simulation(const SceneDef& scene);
StepReport step(Simulation& sim);

// Applies new material/solver settings from `scene` without touching the state; rebuilds
// the mesh (and restarts from the initial state) only when the mesh definition changed.
void update_scene(Simulation& sim, const SceneDef& scene);

// Measurements of the current state.
std::vector<double> triangle_det_f(const Simulation& sim);
double min_plane_gap(const Simulation& sim);  // +inf without planes
double total_energy(const Simulation& sim);   // kinetic + elastic + gravity (for stability checks)

}  // namespace invfree
