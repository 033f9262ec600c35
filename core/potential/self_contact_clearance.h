// Self-contact's certificate that nothing is close: what lets the term cost almost nothing
// while the boundary is far from touching itself (every scene has self-contact on by
// default, and most never come near).
//
// Measured at positions y (an accepted, intersection-free state): every boundary node-edge
// pair (edge not incident to the node) within `reach` of each other, found by the broad
// phase, with its slack g = distance(y) - dhat_pair (dhat_pair: self_contact_barrier.h's
// rule); a pair not listed is farther than reach, so its slack is at least
// far = reach - dhat. reach = dhat + the mean rest edge length.
// A point-edge distance moves by at most the largest motion of the edge's ends relative to
// the node, and not at all under a common translation. So at positions z whose boundary
// nodes moved by u_i from y:
//  - every pair keeps at least  slack - 2 m,  m the largest |u_i - t| (t one common
//    translation, the displacements' mid-range), slack the smallest of all;
//  - a listed pair keeps at least  g - max(|u_a - u_n|, |u_b - u_n|),
//  - an unlisted one at least  far - 2 m.
// Where a bound is positive (less a rounding allowance) the pair is farther than its dhat on
// the whole motion: its barrier and friction are exactly zero, the CCD has nothing to stop,
// and no crossing can begin there (from the intersection-free y, straight to z, that pair
// never touches; a first crossing of two boundary segments always begins with an end
// touching the other segment). So:
//  - while 2 m < slack nothing needs the broad phase, the CCD or the exact check;
//  - while 2 m < far the listed pairs whose own bound is not positive are the only ones
//    that can be within their dhat: they are the candidates, without a broad phase (the same
//    active pairs, in the same order, as the broad phase's list: sums are bit-identical);
//  - otherwise the broad phase runs, and the step's invariant check measures again.
// Motions are bounded over the boxes of whole line-search paths, as the broad phase's boxes
// are (each node anywhere in the box of its path: the friction stop's trials too).
// The certificate depends only on (y, its measurement, dhat): not on how z was reached.
#pragma once

#include <vector>

#include "collision/broad_phase.h"
#include "potential/self_contact_barrier.h"

namespace invfree {

struct SelfContactClearance {
  VecX at;                   // boundary node positions where measured (Boundary::nodes order)
  double slack = -INFINITY;  // the smallest slack of any pair; -infinity: none measured
  double far = -INFINITY;    // the slack every pair not listed has at least
  double dhat = 0.0;         // the scene dhat of the measurement
  double margin = 0.0;       // rounding allowance (m)
  std::vector<PointEdgePair> pairs;  // the pairs within reach at `at`, sorted
  std::vector<double> pair_slack;    // their slack at `at`
  // Each boundary node's displacement box since `at` over the motion last asked about.
  std::vector<Vec2> lo, hi;
};

// Measures at x (x must be intersection-free: the caller has checked it exactly).
void measure_clearance(const Boundary& boundary, const std::vector<Vec2>& rest, const VecX& x,
                       const SelfContactParams& params, BroadPhaseGrid& grid,
                       SelfContactClearance& out);

// The motion z -> z + alpha p (p null: the point z) since the measurement: a bound m on
// how far any point of the nodes' displacement boxes lies from their common mid-range t:
// half the diagonal of all of them where that is enough for is_clear, otherwise the
// farthest corner of any node's box (then kept in c for near_pairs). +infinity when
// nothing was measured.
double clearance_motion(const Boundary& boundary, SelfContactClearance& c, const VecX& z,
                        const VecX* p, double alpha);

// True when no pair can be within its dhat on a motion of size m (see above).
inline bool is_clear(const SelfContactClearance& c, double dhat, double m) {
  return c.dhat == dhat && 2.0 * m + c.margin < c.slack;
}

// After clearance_motion (m its result) where is_clear is not: when the listed pairs answer
// for every pair (2 m < far), `out` = those of them that may come within their dhat on that
// motion, sorted, and true; false when the broad phase must run.
bool near_pairs(const Boundary& boundary, const SelfContactClearance& c, double dhat, double m,
                std::vector<PointEdgePair>& out);

}  // namespace invfree
