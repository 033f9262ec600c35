// IPC self-contact: the log barrier on the squared point-edge distance D = d^2 of every
// boundary node against every boundary edge not incident to it (any body, its own
// included), as in the solid-sim-tutorial's 7_self_contact:
//   B(D) = 1/2 a dhat kappa/8 (s - 1) ln s,   s = D / dhat^2,   for D < dhat^2; 0 beyond,
// with a the node's contact area (Boundary::node_area). This is the ground's b of
// potential/barrier.h (a dhat kappa/2 (s - 1) ln s) evaluated on D with dhat^2 for dhat,
// kappa / (4 dhat) for kappa and a / 2 for a:
//  - kappa/8 instead of kappa/2: on d^2, (s^2 - 1) ln s^2 ~ 4 (s - 1)^2 near dhat, so the
//    stiffness d^2B/dd^2 at d = dhat is the ground's a kappa / dhat before the factor 1/2
//    (the tutorial's "consistency to linear elasticity");
//  - the factor 1/2: two facing surfaces each bring their nodes against the other's edges,
//    so each contact is counted twice (a pair's stiffness at dhat is a kappa / (2 dhat)).
//
// d-hat rule (pair_dhat): a pair of one body's own node and edge uses
//   dhat_pair = min(scene dhat, kRestDistanceFraction * its rest distance),
// and a pair across two bodies the scene's dhat. At rest, or moved rigidly, every pair of a
// body is at its rest distance, at least twice its dhat_pair, so a body at rest or falling
// freely feels exactly zero self-contact force at any resolution (a fine mesh's neighbours
// along the boundary are closer than the scene's dhat: at n_seg 256 an edge is 3.9 mm and
// dhat 1 cm). It is the "exclude pairs close at rest" (ipc-toolkit leaves such
// exclusions to a user can_collide predicate) made gradual: dropped pairs would leave a
// fold a few edges wide to the CCD alone, which stalls the line search there; here their
// dhat shrinks with their rest distance instead, and one dhat per pair keeps B smooth. A
// pair feels force only when its distance falls below half its rest distance, e.g. a node
// two edges away along a straight side when the edge between is compressed below half
// its length, or when the angle there closes below 30 degrees; pairs far apart along the
// boundary (a fold's two faces, another body) keep the scene's dhat.
//
// Inputs: the boundary, the rest positions (per mesh node, the dhat rule), candidate pairs
// (collision/broad_phase.h), positions x (2 per node; entries past 2N are ignored).
// Outputs: value (+infinity when a pair touches), gradient and PSD-projected 6x6 Hessians.
#pragma once

#include <span>
#include <vector>

#include "potential/barrier.h"
#include "potential/point_edge_distance.h"
#include "scene/boundary.h"

namespace invfree {

constexpr double kRestDistanceFraction = 0.5;

struct SelfContactParams {
  double dhat = 0.01;  // the scene's dhat (m)
  double kappa = 1e5;
};

// A local 6x6 block over (node, edge[0], edge[1]), mesh node indices.
struct PointEdgeHessian {
  std::array<int, 3> nodes;
  Mat6 hessian;
};

inline double pair_dhat(double scene_dhat, double rest_distance, bool same_body) {
  return same_body ? std::min(scene_dhat, kRestDistanceFraction * rest_distance) : scene_dhat;
}

// B as the ground's barrier function of D (see above). area: the node's contact area.
inline BarrierParams squared_distance_barrier(double dhat, double kappa, double area) {
  return {dhat * dhat, 0.25 * kappa / dhat, 0.5 * area};
}

// One pair, B(D(p, a, b)); `barrier` from squared_distance_barrier.
double point_edge_barrier(const Vec2& p, const Vec2& a, const Vec2& b,
                          const BarrierParams& barrier);
Vec6 point_edge_barrier_gradient(const Vec2& p, const Vec2& a, const Vec2& b,
                                 const BarrierParams& barrier);
// Exact Hessian B'' dD dD^T + B' d2D (project = false) or its projection onto the PSD cone,
// the negative eigenvalues clamped to zero: by eigen-decomposition in the point-line regime
// (of the 4x4 block that remains once the two translations, which H annihilates, are
// removed), in closed form in the point-point ones (see the .cpp).
Mat6 point_edge_barrier_hessian(const Vec2& p, const Vec2& a, const Vec2& b,
                                const BarrierParams& barrier, bool project);

// The barrier's parameters for one candidate pair (its dhat by the rule above).
BarrierParams pair_barrier(const Boundary& boundary, const std::vector<Vec2>& rest,
                           const PointEdgePair& pair, const SelfContactParams& params);

// Room for the sums over pairs to run over the threads: each pair's terms are computed
// concurrently, in fixed blocks of pairs, into its own slots, and then added in pair order,
// the serial loop's order, so the sums have the same bits on any number of threads, and
// as without it. Grown to the largest pair list seen, never shrunk (no allocation once
// grown).
struct PairSumScratch {
  std::vector<double> values;            // per pair: its barrier, 0 beyond its dhat
  std::vector<unsigned char> active;     // per pair: within its own dhat
  std::vector<Vec6> gradients;           // per active pair: its gradient
  std::vector<PointEdgeHessian> blocks;  // per active pair: scale * its projected Hessian
  void reserve(size_t pairs);
};

// Sums over the candidate pairs. Pairs at or beyond the scene's dhat cost one distance.
// Without `scratch` (or with few pairs) they run on the calling thread.
double self_contact_energy(const Boundary& boundary, const std::vector<Vec2>& rest,
                           std::span<const PointEdgePair> pairs, const VecX& x,
                           const SelfContactParams& params, PairSumScratch* scratch = nullptr);
// gradient += scale * dE/dx; appends scale * each active pair's projected Hessian.
void add_self_contact_gradient_hessian(const Boundary& boundary, const std::vector<Vec2>& rest,
                                       std::span<const PointEdgePair> pairs, const VecX& x,
                                       const SelfContactParams& params, double scale,
                                       VecX& gradient, std::vector<PointEdgeHessian>& hessians,
                                       PairSumScratch* scratch = nullptr);

}  // namespace invfree
