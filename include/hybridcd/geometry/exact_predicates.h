// SPDX-License-Identifier: BSD-3-Clause
// Orientation predicates with exact signs for double-precision input.
//
// Each predicate first evaluates the determinant in floating point together with a forward
// error bound (Shewchuk's static filter). When the magnitude of the result exceeds the bound,
// its sign is certain. Otherwise -- near-degenerate input, or magnitudes so huge or tiny that
// the bound itself overflows or underflows -- the determinant is recomputed in exact rational
// arithmetic. The exact path is rare on generic input and makes touching, coplanar and
// collinear configurations decide the same way every time.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

namespace hcd
{
/// Sign (-1, 0, +1) of det[b-a, c-a, d-a]: positive when d lies on the side of the plane
/// through a, b, c that its normal (b-a) x (c-a) points to.
int orient3d(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d);

/// Sign (-1, 0, +1) of the 2D determinant det[b-a, c-a] for points (x, y): positive when a, b, c
/// turn counter-clockwise.
int orient2d(double ax, double ay, double bx, double by, double cx, double cy);

/// How often the exact fallback has run in this process, all threads together (for tests and
/// benchmarks: compare two readings taken around single-threaded work).
unsigned long long exactPredicateFallbacks();
}  // namespace hcd
