// The exact sign of the orientation of three points, the determinant
//   orient(a, b, c) = (b - a) x (c - a):  +1 counter-clockwise, -1 clockwise, 0 collinear,
// for any double coordinates whose pairwise products neither overflow nor underflow
// (|coordinate| between about 1e-145 and 1e145, or zero).
// Method (Shewchuk 1997, "Adaptive precision floating-point arithmetic and fast robust
// geometric predicates"): first the plain floating-point determinant with his forward error
// bound, which decides all but nearly collinear triples; otherwise the determinant is
// expanded into six products of input coordinates,
//   ax by - ax cy + bx cy - bx ay + cx ay - cx by,
// each split exactly into a rounded product and its error by fma (TwoProduct), and the
// twelve terms are summed exactly into a non-overlapping expansion (Grow-Expansion with
// TwoSum); the sign of such an expansion is the sign of its largest component.
#pragma once

#include "types.h"

namespace invfree {

int orientation(const Vec2& a, const Vec2& b, const Vec2& c);

// The exact sign by the expansion alone, without the floating-point filter (for tests).
int orientation_exact(const Vec2& a, const Vec2& b, const Vec2& c);

}  // namespace invfree
