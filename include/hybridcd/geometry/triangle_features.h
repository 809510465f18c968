// SPDX-License-Identifier: BSD-3-Clause
// The squared distance of two disjoint closed triangles as the least of their fifteen features,
// measured four at a time in SIMD lanes, and the same arithmetic feature by feature as the reference
// the lanes are held to, bit for bit.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

namespace hcd
{
/// The squared distance of the closed triangles (a0, a1, a2) and (b0, b1, b2), which must not
/// intersect: the least of
/// - each vertex's squared distance to the point of the other triangle it projects onto, for the
///   six vertices that project inside the other triangle (its barycentric weights all >= 0), and
/// - the nine edge pairs' squared distances (closed segments, Ericson 5.1.9).
/// A vertex projecting outside the other triangle is nearest its boundary, which the edge pairs
/// through that vertex measure, so in exact arithmetic nothing is missed. Every value is the
/// distance between two computed points of the triangles, so none falls below the true distance by
/// more than rounding (slivers included: their inside test may err, their points may not). The
/// edge pairs' nearest points come from cross products, so nearly parallel edges keep them to
/// rounding of the coordinates; a sliver's inside test that errs leaves its vertex to the edge
/// pairs, which may then exceed the distance by about the rounding of its normal.
/// The features go through SIMD lanes (Google Highway, the widest instruction set the machine has,
/// chosen at run time); coordinates beyond 1e75 in magnitude, or not finite, go to the reference.
double triangleFeaturesSquared(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                               const Vec3 &b2);

/// triangleFeaturesSquared's arithmetic one feature at a time in scalar code: the same number, bit
/// for bit, for every input (features that come out NaN are passed over).
double triangleFeaturesSquaredReference(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                                        const Vec3 &b2);
}  // namespace hcd
