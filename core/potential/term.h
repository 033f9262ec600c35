// The contract every term of the incremental potential meets. It is checked at compile
// time (the sums are templates over the list in incremental_potential.h: no virtual calls
// in the hot loops), in the shape of ipc-toolkit's potential.hpp: the sums over terms are
// written once (incremental_potential.cpp, the explicit integrator, the energy report);
// each term supplies its own value and derivatives, and optionally a largest safe step.
//
// Every term has
//   bool on;                               switched on by the scene (core/make_terms.cpp)
//   static constexpr EnergyKind kind;      where the energy report bins it
// A node term (node_term.h: gravity, the planes' barriers, ground friction) is evaluated
// node by node, fused with inertia in one loop over the nodes:
//   double value(const NodeState&) const;
//   void add_derivatives(const NodeState&, double scale, NodeDerivatives&) const;
// A whole-mesh term (elasticity, springs, the grab, self-contact, the ceiling's penalty):
//   static constexpr bool scaled_by_h2;    false for the ceiling's penalty alone
//   double value(const TermPoint&, double scale) const;             scale * its energy
//   void add_derivatives(const TermPoint&, double scale, Assembly&) const;
// Optional, found by the concepts below:
//   double max_step(const TermPoint&, const VecX& dir, double alpha) const;
//       the largest step in [0, alpha] along dir that keeps the term finite (inversion,
//       CCD); a node term's filter (the planes) is, over the nodes [first, last) of `nodes`
//   double max_step(const VecX& z, int nodes, int first, int last, const VecX& dir,
//                   double alpha) const;
//       a filter that keeps state (self-contact's candidates) also has
//   double path_step(const TermPoint&, const VecX& trial) const;   (0, 1] of z -> trial
//   void begin(const TermPoint&) const;     at Newton's start point (candidates there)
//   explicit integration's force: a node term's
//   void add_explicit_force(const NodeState&, const Vec2& v, double h, NodeDerivatives&) const
//       (default: add_derivatives with scale 1), a whole-mesh term's
//   void add_explicit_force(const TermPoint&, VecX& gradient) const  (none: no force)
//   void add_energy_by_kind(const TermPoint&, EnergyBins&) const   (default: bins[kind])
// A control term (the ceiling's penalty) steers Newton's stopping test:
//   bool settle(int nodes, VecX& z);  bool at_target(int nodes, const VecX&, double tol) const;
//   void tighten();  double hessian_floor() const;
// Caches a term keeps between calls of one step live in StepCaches (step_caches.h) and
// reach it through TermPoint::caches: nothing is written behind a const reference.
#pragma once

#include <array>
#include <concepts>
#include <vector>

#include "linalg/sparse_hessian.h"
#include "potential/node_term.h"
#include "scene/mesh.h"
#include "types.h"

namespace invfree {

enum class EnergyKind { Elastic, Gravity, Contact, Friction, Control, Load, Count };

struct StepCaches;  // step_caches.h

// Where a whole-mesh term is evaluated: the unknowns z = [x; c] and the step's frozen data.
struct TermPoint {
  const VecX& z;
  const Mesh& mesh;
  const VecX& x_start;  // x^n: lagged friction's reference
  StepCaches& caches;
  int node_count() const { return mesh.node_count(); }
};

// Where a term adds its derivatives. A term whose Hessian blocks fall outside the pattern
// sets `outgrown` and lists every node pair it needs in `needed_pairs`; the assembly then
// rebuilds the pattern (its version changes, so the solve redoes its symbolic analysis)
// and starts again.
struct Assembly {
  Assembly(VecX& g, SparseHessian& h) : gradient(g), hessian(h) {}
  VecX& gradient;
  SparseHessian& hessian;
  bool outgrown = false;
  std::vector<std::array<int, 2>> needed_pairs;
};

// The energy report's bins (energy_report.h), one per EnergyKind.
struct EnergyBins {
  std::array<double, static_cast<int>(EnergyKind::Count)> value{};
  double& operator[](EnergyKind k) { return value[static_cast<int>(k)]; }
  double operator[](EnergyKind k) const { return value[static_cast<int>(k)]; }
};

template <class T>
concept NodeTerm = requires(const T t, const NodeState& s, NodeDerivatives& d) {
  { t.on } -> std::convertible_to<bool>;
  { T::kind } -> std::convertible_to<EnergyKind>;
  { t.value(s) } -> std::convertible_to<double>;
  t.add_derivatives(s, 1.0, d);
};

template <class T>
concept MeshTerm = requires(const T t, const TermPoint& at, Assembly& a) {
  { t.on } -> std::convertible_to<bool>;
  { T::kind } -> std::convertible_to<EnergyKind>;
  { T::scaled_by_h2 } -> std::convertible_to<bool>;
  { t.value(at, 1.0) } -> std::convertible_to<double>;
  t.add_derivatives(at, 1.0, a);
};

template <class T>
concept HasMaxStep = requires(const T t, const TermPoint& at, const VecX& dir) {
  { t.max_step(at, dir, 1.0) } -> std::convertible_to<double>;
};
template <class T>
concept HasNodeMaxStep = requires(const T t, const VecX& z, const VecX& dir) {
  { t.max_step(z, 1, 0, 1, dir, 1.0) } -> std::convertible_to<double>;
};
template <class T>
concept HasPathStep = requires(const T t, const TermPoint& at, const VecX& trial) {
  { t.path_step(at, trial) } -> std::convertible_to<double>;
};
template <class T>
concept HasBegin = requires(const T t, const TermPoint& at) { t.begin(at); };
template <class T>
concept ControlTerm = requires(T t, const T ct, VecX& z) {
  { t.settle(1, z) } -> std::convertible_to<bool>;
  { ct.at_target(1, z, 1.0) } -> std::convertible_to<bool>;
  t.tighten();
  { ct.hessian_floor() } -> std::convertible_to<double>;
};

template <class T>
concept HasNodeExplicitForce =
    requires(const T t, const NodeState& s, const Vec2& v, NodeDerivatives& d) {
      t.add_explicit_force(s, v, 1.0, d);
    };
template <class T>
concept HasMeshExplicitForce = requires(const T t, const TermPoint& at, VecX& g) {
  t.add_explicit_force(at, g);
};
template <class T>
concept HasEnergyByKind = requires(const T t, const TermPoint& at, EnergyBins& bins) {
  t.add_energy_by_kind(at, bins);
};

}  // namespace invfree
