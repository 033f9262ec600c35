// Continuous collision detection for the line search: the largest step fraction along a
// direction for which no boundary node touches a boundary edge anywhere on the way.
//
// Additive CCD (Li, Kaufman and Jiang 2021, "Codimensional Incremental Potential Contact";
// the solid-sim-tutorial's narrow_phase_CCD, ipc-toolkit's AdditiveCCD). With the pair's
// common motion removed (the distance does not change under a translation), the distance d
// moves at most at rate L = |dp| + max(|da|, |db|) per unit step, so advancing by
// (1 - eta) d / L cannot reach contact: the loop advances by such steps and stops before
// the distance falls below eta d0 (eta = kCcdGapFraction, d0 the start distance).
// Why additive rather than exact root-finding: it needs only the point-edge distance, which
// floating point evaluates accurately, where the collinearity quadratic of an exact 2D CCD
// has degenerate cases (vanishing leading coefficient, a point sliding along the edge's
// line, a zero-length edge) and a root that rounding can put on either side of the
// contact; every time it returns keeps a gap of about eta d0 > 0 (never a step that ends at
// zero distance, which a log barrier could not evaluate anyway), and every fraction below
// it is also collision-free, so the line search may halve it freely. Its cost grows when a
// node slides along an edge at a small distance (about L t / d steps): an iteration cap
// bounds it, and then the time reached so far is returned (safe: each step is certified).
// Every returned time is checked once more by evaluating the distance at x + t dx exactly
// as the caller will, and halved while that is not positive.
#pragma once

#include <span>

#include "scene/boundary.h"

namespace invfree {

constexpr double kCcdGapFraction = 0.1;
constexpr int kCcdMaxIterations = 10000;

// Largest t in [0, t_max] (0 when the point is already on the edge) such that p + s dp
// never touches the segment a + s da, b + s db for s in [0, t].
double point_edge_ccd(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& dp, const Vec2& da,
                      const Vec2& db, double t_max);

// The smallest of the above over the candidate pairs (collision/broad_phase.h, built over
// the path x -> x + alpha_max p): the largest alpha in [0, alpha_max] that moves no boundary
// node through a boundary edge. x, p: 2 per mesh node (entries past 2N ignored).
double self_contact_step(const Boundary& boundary, std::span<const PointEdgePair> pairs,
                         const VecX& x, const VecX& p, double alpha_max);

}  // namespace invfree
