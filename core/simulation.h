// A running simulation: the scene, its mesh, the state and the solver's private
// workspace. `step` advances one time step by implicit Euler (projected Newton on the
// incremental potential, core/solver/newton.h) or symplectic Euler, checks the
// invariants, and leaves the state untouched when the step fails.
// The state is every value a step reads besides the scene and the mesh: x, v, the
// ceiling's actual and nominal heights, its penalty stiffness (the warm start of the next
// step's penalty), time and step count. Copying these fields into a simulation of the same
// scene restarts the run there; the result is bit-identical when the linear solve is
// direct, and within Newton's tolerance with PCG, whose reused factor (workspace) is not
// part of the state.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "potential/pull_spring.h"
#include "scene/scene.h"
#include "scene/tractions.h"
#include "solver/step_status.h"

namespace invfree {

struct StepReport {
  StepStatus status = StepStatus::Ok;
  int newton_iterations = 0;
  double residual = 0.0;
  // Implicit Euler: the incremental potential at the accepted state. Symplectic Euler:
  // total_energy (kinetic + elastic + gravity) at the step's start.
  double energy = 0.0;
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
  // Of the above and the rest: self-contact's broad phase, CCD, energy, derivatives and
  // Hessian blocks, and its intersection check (0 without self-contact).
  double self_contact_ms = 0.0;
  int factorizations = 0;
  int pcg_iterations = 0;
  int energy_evaluations = 0;
  int stopped_nodes = 0;  // Newton's safeguards at work (solver/newton.h)
  int expanded_steps = 0;
  int penalty_doublings = 0;  // the ceiling's penalty doubled (converged short of the target)
};

struct StepWorkspace;  // solver/step_workspace.h

struct Simulation {
  SceneDef scene;
  Mesh mesh;
  std::vector<double> node_mass;
  double ceiling_mass = 0.0;
  // Only when the scene's bodies differ or a body is a meshed shape (scene/scene_mesh.h),
  // otherwise empty: each node's plane-contact area, each triangle's material.
  std::vector<double> node_contact_area;
  std::vector<Lame> triangle_lame;
  // Only with [traction] tables (scene/tractions.h), otherwise empty: the dead loads'
  // force per node (2N) and the pressure's edges.
  VecX node_load;
  std::vector<PressureEdge> pressure_edges;
  // State.
  VecX x, v;                       // 2N each
  double ceiling_y = 0.0;          // actual height (within tol * h of ceiling_nominal)
  double ceiling_nominal = 0.0;    // prescribed height
  double ceiling_stiffness = 0.0;  // the last step's penalty stiffness (0: none yet)
  double time = 0.0;
  long step_count = 0;
  // Input: the live window's grab, applied by every step while on.
  PullSpring pull;
  // The solver's workspace (private; built once per mesh).
  std::unique_ptr<StepWorkspace> workspace;

  Simulation();
  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;
  ~Simulation();
};

// Builds a simulation from a validated scene (see validate_scene).
Simulation make_simulation(const SceneDef& scene);
StepReport step(Simulation& sim);

// Applies new material/solver settings from `scene` without touching the state; rebuilds
// the mesh (and restarts from the initial state) when needs_new_mesh(sim.scene, scene).
void update_scene(Simulation& sim, const SceneDef& scene);
// True when going from `old` to `next` changes the mesh, the masses or the unknowns (the
// ceiling's), so that the simulation must be built anew.
bool needs_new_mesh(const SceneDef& old, const SceneDef& next);

// Measurements of the current state.
std::vector<double> triangle_det_f(const Simulation& sim);
double min_plane_gap(const Simulation& sim);  // +inf without planes
// Smallest distance from a boundary node to a boundary edge not incident to it (m), among
// pairs closer than the scene's dhat; +inf without self-contact or when none is that close.
double min_self_gap(const Simulation& sim);
double total_energy(const Simulation& sim);  // kinetic + elastic + gravity (for stability checks)
// The linear solver that runs: "ldlt", "cholmod" or "pcg+ldlt" ("" before the first
// implicit step's setup).
const char* linear_solver_backend(const Simulation& sim);

}  // namespace invfree
