// The incremental potential of one implicit Euler step (lecture 9's demo, IPC's form):
//   E(x, c) = 1/2 |x - x_tilde|^2_M                                 inertia.h
//           + h^2 [ sum_i -m_i g.x_i                                gravity.h
//                   + sum_i b(y_i - y_ground) + sum_i b(c - y_i)    plane_barrier.h
//                   + sum_i D_i(x_i)                                friction.h
//                   + sum_t area_t Psi(F_t)                         elasticity.h
//                   + k_pull/2 |x_p - target|^2                     pull_spring.h
//                   + sum_s 1/2 k l^2 (|d_s|^2/l^2 - 1)^2           mass_spring.h
//                   + sum_pairs B(D(node, edge)) + lagged friction  self_contact.h
//                   - sum_i f_i.x_i + p A(x) ]                      boundary_load.h
//           + 1/2 k (c - c_target)^2                                ceiling_penalty.h
// over the node coordinates x (2N) and, when the scene has a ceiling, its height c as one
// extra unknown. Every term meets the contract of term.h; StepProblem lists them once
// (for_each_node_term, for_each_mesh_term: the order every sum adds them in), and the sums
// (term_sums.h) are written once over that list. The node terms are fused with inertia in
// one loop over the nodes. A mass-spring scene (the course's chapters 1-5) has springs
// instead of the triangles' elasticity; fixed nodes (fixed_dofs.h) are eliminated from the
// gradient and Hessian. core/make_terms.cpp builds the terms from a scene. A static step
// (solver.integrator = "static") has no inertia: the same sum without its first line.
// Inputs: a StepProblem (everything frozen for the step), its caches and z = [x; c].
// Outputs: the value (+infinity outside the feasible set: an inverted neo-Hookean
// triangle or a node on or through a plane), the gradient and projected Hessian, and the
// largest safe step along a direction (the terms' filters).
#pragma once

#include <vector>

#include "linalg/sparse_hessian.h"
#include "potential/boundary_load.h"
#include "potential/ceiling_penalty.h"
#include "potential/elasticity.h"
#include "potential/fixed_dofs.h"
#include "potential/friction.h"
#include "potential/gravity.h"
#include "potential/inertia.h"
#include "potential/mass_spring.h"
#include "potential/plane_barrier.h"
#include "potential/pull_spring.h"
#include "potential/self_contact.h"
#include "potential/step_caches.h"
#include "scene/mesh.h"

namespace invfree {

struct StepProblem {
  const Mesh* mesh = nullptr;
  const std::vector<double>* mass = nullptr;  // per node
  double h = 0.01;
  VecX x_tilde;         // x^n + h v^n (2N): inertia's target
  VecX x_start;         // x^n (2N): lagged friction's reference
  bool inertia = true;  // false: a static step (equilibrium, no 1/2 |x - x_tilde|^2_M)
  // A bound of E's rounding error beyond Newton's 64 eps (|E| + 1) (newton.cpp): in a static
  // step, 8 eps h^2 sum_t area_t mu_t, the rounding of mu/2 (tr F^T F - 2) - mu ln J, two
  // terms of size mu that cancel near F = I; 0 in a dynamic step, whose inertia dominates.
  double energy_rounding = 0.0;

  // The terms.
  Gravity gravity;
  DeadLoad dead_load;
  GroundBarrier ground;
  GroundFriction friction;
  CeilingBarrier ceiling;  // on: the ceiling's height is the unknown z[2N]
  Elasticity elasticity;
  PressureLoad pressure;
  CeilingPenalty ceiling_penalty;
  PullSpring pull;
  MassSpring springs;
  SelfContact self_contact;
  // A constraint, not a term: eliminated after the terms are assembled.
  FixedDofs fixed;

  // THE list, in the order every sum adds the terms.
  template <class Fn>
  void for_each_node_term(Fn&& fn) const {
    node_terms(*this, fn);
  }
  template <class Fn>
  void for_each_mesh_term(Fn&& fn) const {
    mesh_terms(*this, fn);
  }
  template <class Fn>
  void for_each_mesh_term(Fn&& fn) {
    mesh_terms(*this, fn);
  }

  int node_count() const { return mesh->node_count(); }
  int dof_count() const { return 2 * node_count() + (ceiling.on ? 1 : 0); }
  NodeState node_state(const double* z, int i) const {
    return {i,
            z[2 * i],
            z[2 * i + 1],
            (*mass)[i],
            x_start[2 * i],
            ceiling.on ? z[2 * node_count()] : 0.0,
            x_start[2 * i + 1]};
  }

 private:
  template <class Self, class Fn>
  static void node_terms(Self& p, Fn& fn) {
    fn(p.gravity);
    fn(p.dead_load);
    fn(p.ground);
    fn(p.friction);
    fn(p.ceiling);
  }
  template <class Self, class Fn>
  static void mesh_terms(Self& p, Fn& fn) {
    fn(p.elasticity);
    fn(p.pressure);
    fn(p.ceiling_penalty);
    fn(p.pull);
    fn(p.springs);
    fn(p.self_contact);
  }
};

double ip_energy(const StepProblem& p, StepCaches& caches, const VecX& z);
// A term's Hessian blocks outside the pattern rebuild it (hessian.pattern_version
// changes; the solve redoes its symbolic analysis), unless the Hessian keeps them as
// couplings (SparseHessian::keep_couplings: no rebuild, no new analysis).
void ip_gradient_hessian(const StepProblem& p, StepCaches& caches, const VecX& z, VecX& gradient,
                         SparseHessian& hessian);
// The largest alpha in [0, 1] that every term's filter allows along dir (the planes, the
// inversion filter where the model needs det F > 0, self-contact's CCD).
double largest_safe_step(const StepProblem& p, StepCaches& caches, const VecX& z, const VecX& dir);
// The largest fraction of the straight motion z -> trial that the stateful filters allow.
double path_step(const StepProblem& p, StepCaches& caches, const VecX& z, const VecX& trial);
// The terms' preparation at Newton's start point (self-contact's candidates there).
void begin_terms(const StepProblem& p, StepCaches& caches, const VecX& z);

// The control terms (the ceiling's penalty), for Newton's stopping test.
bool settle_controls(StepProblem& p, VecX& z);  // true when z changed
bool controls_at_target(const StepProblem& p, const VecX& z, double tolerance);
void tighten_controls(StepProblem& p);
// A lower bound of the projected Hessian's eigenvalues (linalg/pcg.h's PCG bound):
// inertia's smallest node mass, each control term's floor, 1 for eliminated rows.
double hessian_lower_bound(const StepProblem& p, double min_node_mass);

}  // namespace invfree
