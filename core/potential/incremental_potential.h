// The incremental potential of one implicit Euler step (lecture 9's demo, IPC's form):
//   E(x, c) = 1/2 |x - x_tilde|^2_M                                 inertia.h
//           + h^2 [ sum_t area_t Psi(F_t)                           elasticity.h
//                   - sum_i m_i g.x_i                               gravity.h
//                   + sum_i b(y_i - y_ground) + sum_i b(c - y_i)    plane_barrier.h
//                   + sum_i D_i(x_i)                                friction.h
//                   + k_pull/2 |x_p - target|^2                     pull_spring.h
//                   + sum_s 1/2 k l^2 (|d_s|^2/l^2 - 1)^2 ]         mass_spring.h
//           + 1/2 k (c - c_target)^2                                ceiling_penalty.h
//           + h^2 [ sum_pairs B(D(node, edge)) + lagged friction ]  self_contact.h
// over the node coordinates x (2N) and, when the scene has a ceiling, its height c as one
// extra unknown. Each term is one file of free functions and is evaluated only when the
// scene switches it on; the terms are listed once, in for_each_node_term below and in the
// sums of incremental_potential.cpp. A mass-spring scene (the course's chapters 1-5) has
// springs instead of the triangles' elasticity; fixed nodes (fixed_dofs.h) are eliminated
// from the gradient and Hessian.
// Inputs: a StepProblem (everything frozen for the step) and z = [x; c].
// Outputs: the value (+infinity outside the feasible set: an inverted neo-Hookean
// triangle or a node on or through a plane), the gradient and projected Hessian, and the
// largest feasible step along a direction (the terms' filters).
#pragma once

#include <vector>

#include "linalg/sparse_hessian.h"
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
#include "scene/mesh.h"

namespace invfree {

struct StepProblem {
  const Mesh* mesh = nullptr;
  const std::vector<double>* mass = nullptr;  // per node
  double h = 0.01;
  VecX x_tilde;  // x^n + h v^n (2N): inertia's target
  VecX x_start;  // x^n (2N): lagged friction's reference

  Elasticity elasticity;
  Gravity gravity;
  GroundBarrier ground;
  GroundFriction friction;
  CeilingBarrier ceiling;  // on: the ceiling's height is the unknown z[2N]
  CeilingPenalty ceiling_penalty;
  PullSpring pull;
  MassSpring springs;
  FixedDofs fixed;
  SelfContact self_contact;  // on: its candidates come from the line search's filter

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
};

// The per-node terms scaled by h^2, in the order they are summed.
template <class Fn>
void for_each_node_term(const StepProblem& p, Fn&& fn) {
  fn(p.gravity);
  fn(p.ground);
  fn(p.friction);
  fn(p.ceiling);
}

double ip_energy(const StepProblem& p, const VecX& z);
// With self-contact on, a contact block outside the Hessian's pattern rebuilds the pattern
// (hessian.pattern_version changes; the caller redoes the symbolic analysis).
void ip_gradient_hessian(const StepProblem& p, const VecX& z, VecX& gradient,
                         SparseHessian& hessian);
// The largest alpha in (0, 1] that every filter allows along direction dir: the planes'
// (plane_barrier.h) and, when the model needs det F > 0, the inversion filter's. The
// self-contact CCD, which runs the broad phase, is applied on top by Newton
// (solver/self_contact_filter.h).
double largest_feasible_step(const StepProblem& p, const VecX& z, const VecX& dir);

}  // namespace invfree
