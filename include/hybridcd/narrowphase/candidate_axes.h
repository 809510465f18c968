// SPDX-License-Identifier: BSD-3-Clause
// The finite set of directions on which two convex polytopes' separation and penetration are decided.
//
// For full-dimensional polytopes the facets of their Minkowski difference have normals among the
// face normals of both pieces and the cross products of an edge of one with an edge of the other, so
// the separating-axis test and the penetration depth only need those directions. A degenerate
// difference (a segment or point against a flat or degenerate piece) has facets that neither supplies;
// for those the extra axes below (edge x normal, in-plane perpendiculars, vertex differences) are added.
#pragma once

#include "hybridcd/narrowphase/convex_piece.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace hcd
{
/// Unit edge directions of `piece` with exact and near-exact parallels removed (a box has twelve
/// edges but three directions): parallel edges give the same cross products.
std::vector<Vec3> distinctEdgeDirections(const ConvexPiece &piece);

/// The interval [lo, hi] of n . p over `points` (empty: lo = +inf, hi = -inf).
inline void projectOnto(const std::vector<Vec3> &points, const Vec3 &n, double &lo, double &hi)
{
    lo = std::numeric_limits<double>::infinity();
    hi = -lo;
    for (const Vec3 &p : points)
    {
        const double s = n.dot(p);
        lo = std::min(lo, s);
        hi = std::max(hi, s);
    }
}

/// Calls `consider(axis)` for every candidate axis of the pair (axes are not normalised and may be
/// zero: `consider` must skip those).
template <class Consider>
void forEachCandidateAxis(const ConvexPiece &a, const ConvexPiece &b, Consider &&consider)
{
    for (const Vec3 &n : a.normals)
        consider(n);
    for (const Vec3 &n : b.normals)
        consider(n);
    const std::vector<Vec3> edgesA = distinctEdgeDirections(a), edgesB = distinctEdgeDirections(b);
    for (const Vec3 &ea : edgesA)
        for (const Vec3 &eb : edgesB)
            consider(ea.cross(eb));
    if (std::min(a.dimension, b.dimension) <= 1)
    {
        for (const Vec3 &ea : edgesA)
            for (const Vec3 &n : b.normals)
                consider(ea.cross(n));
        for (const Vec3 &eb : edgesB)
            for (const Vec3 &n : a.normals)
                consider(eb.cross(n));
        for (const Vec3 &ea : edgesA)
            for (const Vec3 &eb : edgesB)
            {
                const Vec3 k = ea.cross(eb);
                consider(k.cross(ea));
                consider(k.cross(eb));
            }
    }
    if (std::max(a.dimension, b.dimension) <= 1)
        for (const Vec3 &va : a.vertices)
            for (const Vec3 &vb : b.vertices)
            {
                const Vec3 w = vb - va;
                consider(w);
                for (const std::vector<Vec3> *edges : {&edgesA, &edgesB})
                    for (const Vec3 &e : *edges)
                        consider(e.cross(w.cross(e)));
            }
}
}  // namespace hcd
