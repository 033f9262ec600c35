// The incremental potential of one implicit Euler step (lecture 9's demo, IPC's form):
//   E(x, c) = 1/2 |x - x_tilde|^2_M
//           + h^2 [ sum_t area_t Psi(F_t) - sum_i m_i g.x_i
//                   + sum_i b(y_i - y_ground) + sum_i b(c - y_i) + sum_i D_i(x_i) ]
//           + 1/2 k (c - c_target)^2
// over the node coordinates x (2N) and, when the scene has a ceiling, its height c as
// one extra unknown pulled to its prescribed position by a penalty (the demo's moving
// Dirichlet boundary; Newton stiffens k until |c - c_target| / h < tol and then holds c
// fixed). Each term is evaluated only when the scene switches it on.
// Inputs: a StepProblem (everything frozen for the step) and z = [x; c].
// Outputs: the value (+infinity outside the feasible set: an inverted neo-Hookean
// triangle or a node on or through a plane), or the gradient and projected Hessian.
#pragma once

#include <vector>

#include "linalg/sparse_hessian.h"
#include "material/material.h"
#include "potential/contact.h"
#include "scene/mesh.h"

namespace invfree {

struct StepProblem {
  const Mesh* mesh = nullptr;
  const std::vector<double>* mass = nullptr;  // per node
  Model model = Model::NeoHookean;
  Lame lame;
  HessianProjection projection = HessianProjection::Diagonal;
  double h = 0.01;
  VecX x_tilde;  // x^n + h v^n (2N)
  VecX x_start;  // x^n (2N), for friction

  bool gravity_on = false;
  Vec2 gravity = Vec2::Zero();

  BarrierParams barrier;
  bool ground_on = false;
  double ground_y = 0.0;
  bool friction_on = false;
  std::vector<double> friction_weight;  // mu_f lambda_i per node, lagged
  double friction_eps_u = 0.0;          // eps_v h

  bool ceiling_on = false;
  double ceiling_target = 0.0;
  double ceiling_stiffness = 0.0;  // k, already multiplied by the ceiling's mass
  bool ceiling_fixed = false;

  // Optional grab spring (the live window's mouse): + h^2 k/2 |x_node - target|^2, one
  // node pulled toward a target while the user drags it. Off in every scene.
  bool pull_on = false;
  int pull_node = 0;
  Vec2 pull_target = Vec2::Zero();
  double pull_stiffness = 0.0;  // k, N/m

  int node_count() const { return mesh->node_count(); }
  int dof_count() const { return 2 * node_count() + (ceiling_on ? 1 : 0); }
};

double ip_energy(const StepProblem& p, const VecX& z);
void ip_gradient_hessian(const StepProblem& p, const VecX& z, VecX& gradient,
                         SparseHessian& hessian);

// Elastic energy sum_t area_t Psi(F_t) alone (also used by explicit integration and tests).
double elastic_energy(const Mesh& mesh, Model model, const Lame& lame, const VecX& x);
// Adds scale * the elastic gradient to `gradient` (2N entries).
void add_elastic_gradient(const Mesh& mesh, Model model, const Lame& lame, const VecX& x,
                          double scale, VecX& gradient);

}  // namespace invfree
