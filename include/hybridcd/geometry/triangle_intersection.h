// SPDX-License-Identifier: BSD-3-Clause
// Exact intersection tests between closed triangles and segments in 3D.
//
// Two closed triangles intersect exactly when an edge of one meets the other triangle (the
// intersection, if not empty, is a segment or convex polygon whose end points lie on the boundary
// of one of the two). The tests below decide this with orientation predicates only, whose signs
// are exact (exact_predicates.h), so touching at a vertex, along an edge or over a coplanar face
// counts as intersection, consistently.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

namespace hcd
{
/// True when the closed triangles (a0, a1, a2) and (b0, b1, b2) share at least one point.
/// Degenerate triangles (collinear or repeated vertices) are handled as the segments they are.
bool trianglesIntersect(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1, const Vec3 &b2);

/// True when the closed segment pq meets the closed triangle (a, b, c).
bool segmentIntersectsTriangle(const Vec3 &p, const Vec3 &q, const Vec3 &a, const Vec3 &b, const Vec3 &c);

/// True when the closed segments pq and rs share a point.
bool segmentsIntersect(const Vec3 &p, const Vec3 &q, const Vec3 &r, const Vec3 &s);

/// True when a, b, c are collinear (or coincide), decided exactly.
bool isDegenerateTriangle(const Vec3 &a, const Vec3 &b, const Vec3 &c);
}  // namespace hcd
