// Mass-spring elasticity, the course's chapters 1-5 (solid-sim-tutorial's
// MassSpringEnergy.py): one spring per mesh edge plus the second diagonal of every cell
// (the tutorial's square mesh connects both diagonals), each with the energy
//   E = 1/2 k l^2 (|d|^2 / l^2 - 1)^2,   d = x_i - x_j, l its rest length,
//   dE/dx_i = 2 k (|d|^2 / l^2 - 1) d = -dE/dx_j,
//   Hessian [A -A; -A A],  A = 2k / l^2 (2 d d^T + (|d|^2 - l^2) I).
// The 4x4's eigenvalues are twice A's and two zeros, and A's are 2k/l^2 (3|d|^2 - l^2)
// along d and 2k/l^2 (|d|^2 - l^2) across it, so the PSD projection of the 4x4 (the
// tutorial's make_PSD) is [B -B; -B B] with B = A's eigenvalues clamped at zero, in closed
// form. A spring of zero length has A = -2k I, projected to 0.
// Hooke's law instead (the course's chapter 0, [mass_spring] law = "hooke"):
//   E = 1/2 k (|d| - l)^2,   dE/dx_i = k (|d| - l) d / |d| = -dE/dx_j,
//   A = k (d^ d^T + (1 - l / |d|) (I - d^ d^T)),  d^ = d / |d|,
// eigenvalues k along d and k (1 - l/|d|) across it (negative while compressed), so the
// projection clamps the across part at zero. A spring of zero length has no direction:
// gradient 0, A = 0 (the across part's limit, -inf, clamped; unprojected as well).
// The springs are the mesh's (mesh_springs) or listed node pairs (listed_springs, rest
// lengths from the rest positions).
// Inputs: the springs (rest data), k, node positions x (2 per node). Outputs: the energy,
// gradient and (projected) Hessian scattered into a SparseHessian through 16 slots per
// spring. Springs allow any deformation (no inversion filter). A whole-mesh term
// (term.h) of kind Elastic.
#pragma once

#include <array>
#include <vector>

#include "linalg/sparse_hessian.h"
#include "potential/term.h"
#include "scene/mesh.h"
#include "types.h"

namespace invfree {

struct Spring {
  int i = 0, j = 0;
  double rest_length2 = 0.0;  // l^2
};

// The mesh's edges, then for every pair of triangles that share their longest edge (a
// cell's diagonal) the other diagonal; ordered and without duplicates.
std::vector<Spring> mesh_springs(const Mesh& mesh);
// The listed node pairs (the scene's [mass_spring] springs, checked against the mesh by
// find_scene_problem), each with its rest length from the rest positions, in the given order.
std::vector<Spring> listed_springs(const Mesh& mesh, const std::vector<std::array<int, 2>>& pairs);
// Per node, how many springs end there ([gravity] per_spring's weight).
std::vector<double> spring_counts(const std::vector<Spring>& springs, int node_count);
// The node pairs of the springs, for the Hessian's pattern.
std::vector<std::array<int, 2>> spring_node_pairs(const std::vector<Spring>& springs);
// 16 slots per spring: rows (2i, 2i+1, 2j, 2j+1) x the same columns, row-major.
std::vector<int> spring_slots(const std::vector<Spring>& springs, const SparseHessian& hessian);

double spring_energy(const Spring& s, double k, const Vec2& xi, const Vec2& xj);
Vec2 spring_gradient(const Spring& s, double k, const Vec2& xi, const Vec2& xj);  // wrt x_i
// A, or its PSD projection B when `project`.
Mat2 spring_hessian_block(const Spring& s, double k, const Vec2& xi, const Vec2& xj, bool project);
// The same three for Hooke's law.
double hooke_spring_energy(const Spring& s, double k, const Vec2& xi, const Vec2& xj);
Vec2 hooke_spring_gradient(const Spring& s, double k, const Vec2& xi, const Vec2& xj);
Mat2 hooke_spring_hessian_block(const Spring& s, double k, const Vec2& xi, const Vec2& xj,
                                bool project);

struct MassSpring;
double mass_spring_energy(const MassSpring& m, const double* x);
void add_mass_spring_gradient(const MassSpring& m, const double* x, double scale, double* g);
void add_mass_spring_derivatives(const MassSpring& m, const double* x, double scale, double* g,
                                 double* hessian_values);

struct MassSpring {
  static constexpr EnergyKind kind = EnergyKind::Elastic;
  static constexpr bool scaled_by_h2 = true;
  bool on = false;
  double stiffness = 0.0;  // k
  bool project = true;     // the tutorial's make_PSD (off with solver.projection = "none")
  const std::vector<Spring>* springs = nullptr;
  const std::vector<int>* slots = nullptr;
  bool hooke = false;  // Hooke's law (chapter 0) instead of the Green strain's

  double value(const TermPoint& at, double scale) const {
    return scale * mass_spring_energy(*this, at.z.data());
  }
  void add_derivatives(const TermPoint& at, double scale, Assembly& out) const {
    add_mass_spring_derivatives(*this, at.z.data(), scale, out.gradient.data(),
                                out.hessian.values());
  }
  void add_explicit_force(const TermPoint& at, VecX& gradient) const {
    add_mass_spring_gradient(*this, at.z.data(), 1.0, gradient.data());
  }
};


}  // namespace invfree
