// SPDX-License-Identifier: BSD-3-Clause
// Euclidean distances between points, segments and triangles (closed sets).
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

namespace hcd
{
/// Closest point to `p` on the closed triangle (a, b, c) (Voronoi-region walk; handles degenerate triangles).
Vec3 closestPointOnTriangle(const Vec3 &p, const Vec3 &a, const Vec3 &b, const Vec3 &c);

/// Closest points of the closed segments p0p1 and q0q1 (zero-length allowed; Ericson 5.1.9): on
/// return `onP` and `onQ` are the points; the distance is |onP - onQ|.
void closestPointsOfSegments(const Vec3 &p0, const Vec3 &p1, const Vec3 &q0, const Vec3 &q1, Vec3 &onP, Vec3 &onQ);

/// Squared distance between the closed segments p0p1 and q0q1 (zero-length segments allowed).
double segmentSegmentDistanceSquared(const Vec3 &p0, const Vec3 &p1, const Vec3 &q0, const Vec3 &q1);

/// Distance between two closed triangles: 0 when they intersect (decided exactly), otherwise the
/// smallest of the vertex-to-face and edge-to-edge distances (triangle_features.h, the reference
/// arithmetic), in floating point: never below the true distance by more than a few ulps of the
/// coordinates' magnitude, nor above it except through a sliver's inside test
/// (triangle_features.h). The
/// edge pairs are measured in full, endpoints included: they also measure every vertex's distance to
/// the other's edges robustly, where the inside test of a sliver is not.
double triangleDistance(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1, const Vec3 &b2);

/// triangleDistance, bit for bit, for two triangles known not to intersect (e.g. after a collision
/// query answered free), without the intersection test.
double disjointTriangleDistance(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                                const Vec3 &b2);

/// `min(best, disjointTriangleDistance(a, b))`, bit for bit, with less work: the fifteen features
/// measured in SIMD lanes (triangleFeaturesSquared). For branch and bound over triangle pairs.
double disjointTriangleDistanceBelow(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                                     const Vec3 &b2, double best);

/// `triangleDistance(a, b) <= bound`, the same answer in every case, decided with less work: a
/// separating plane first, then the vertex and edge distances in SIMD lanes, and the exact
/// intersection test only when neither settles it. For proximity queries.
bool trianglesWithinDistance(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                             const Vec3 &b2, double bound);
}  // namespace hcd
