// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/geometry/triangle_distance.h"

#include "hybridcd/geometry/triangle_intersection.h"
#include "plane_side.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hcd
{
Vec3 closestPointOnTriangle(const Vec3 &p, const Vec3 &a, const Vec3 &b, const Vec3 &c)
{
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0)
        return a;
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3)
        return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0)
        return a + (d1 / (d1 - d3)) * ab;
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6)
        return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0)
        return a + (d2 / (d2 - d6)) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0)
        return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    const double sum = va + vb + vc;
    if (!(sum > 0.0))
    {
        // Degenerate triangle: the closest point lies on one of its edges.
        Vec3 best = a;
        double bestD = (p - a).squaredNorm();
        for (const auto &[u, v] : {std::pair<const Vec3 *, const Vec3 *>{&a, &b}, {&b, &c}, {&c, &a}})
        {
            const Vec3 e = *v - *u;
            const double len = e.squaredNorm();
            const double t = len > 0.0 ? std::clamp((p - *u).dot(e) / len, 0.0, 1.0) : 0.0;
            const Vec3 q = *u + t * e;
            if ((p - q).squaredNorm() < bestD)
            {
                bestD = (p - q).squaredNorm();
                best = q;
            }
        }
        return best;
    }
    const double denom = 1.0 / sum;
    return a + ab * (vb * denom) + ac * (vc * denom);
}

void closestPointsOfSegments(const Vec3 &p0, const Vec3 &p1, const Vec3 &q0, const Vec3 &q1, Vec3 &onP, Vec3 &onQ)
{
    // Ericson, Real-Time Collision Detection 5.1.9, with the degenerate cases.
    const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
    double s = 0.0, t = 0.0;
    if (!(a > 0.0) && !(e > 0.0))
    {
        onP = p0;
        onQ = q0;
        return;
    }
    if (!(a > 0.0))
        t = std::clamp(f / e, 0.0, 1.0);
    else
    {
        const double c = d1.dot(r);
        if (!(e > 0.0))
            s = std::clamp(-c / a, 0.0, 1.0);
        else
        {
            const double b = d1.dot(d2), denom = a * e - b * b;
            s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
            t = (b * s + f) / e;
            if (t < 0.0)
            {
                t = 0.0;
                s = std::clamp(-c / a, 0.0, 1.0);
            }
            else if (t > 1.0)
            {
                t = 1.0;
                s = std::clamp((b - c) / a, 0.0, 1.0);
            }
        }
    }
    onP = p0 + s * d1;
    onQ = q0 + t * d2;
}

double segmentSegmentDistanceSquared(const Vec3 &p0, const Vec3 &p1, const Vec3 &q0, const Vec3 &q1)
{
    Vec3 onP, onQ;
    closestPointsOfSegments(p0, p1, q0, q1, onP, onQ);
    return (onP - onQ).squaredNorm();
}

namespace
{
// Squared distance of two disjoint closed triangles: they attain it at a vertex of one or between
// two edges.
double disjointTriangleDistanceSquared(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                                       const Vec3 &b2)
{
    double best = std::numeric_limits<double>::infinity();
    const Vec3 *a[3] = {&a0, &a1, &a2}, *b[3] = {&b0, &b1, &b2};
    for (int i = 0; i < 3; ++i)
    {
        best = std::min(best, (*a[i] - closestPointOnTriangle(*a[i], b0, b1, b2)).squaredNorm());
        best = std::min(best, (*b[i] - closestPointOnTriangle(*b[i], a0, a1, a2)).squaredNorm());
        for (int j = 0; j < 3; ++j)
            best = std::min(best, segmentSegmentDistanceSquared(*a[i], *a[(i + 1) % 3], *b[j], *b[(j + 1) % 3]));
    }
    return best;
}

}  // namespace

double triangleDistance(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1, const Vec3 &b2)
{
    if (trianglesIntersect(a0, a1, a2, b0, b1, b2))
        return 0.0;
    return std::sqrt(disjointTriangleDistanceSquared(a0, a1, a2, b0, b1, b2));
}

double disjointTriangleDistance(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                                const Vec3 &b2)
{
    return std::sqrt(disjointTriangleDistanceSquared(a0, a1, a2, b0, b1, b2));
}

namespace
{
/// Signed distances of p0, p1, p2 from the plane of (a0, a1, a2), and how far below the true ones
/// they may be: `error` covers rounding in the normal (amplified for slivers, by 1 / sin of the
/// corner angle) and in the products, with a wide margin. false for a triangle without a plane.
bool planeDistances(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &p0, const Vec3 &p1, const Vec3 &p2,
                    double scale, double (&side)[3], double &error)
{
    const Vec3 e1 = a1 - a0, e2 = a2 - a0;
    const Vec3 n = e1.cross(e2);
    const double length = n.norm();
    if (!(length > 0.0) || !std::isfinite(length))
        return false;
    const Vec3 unit = n / length;
    side[0] = unit.dot(p0 - a0);
    side[1] = unit.dot(p1 - a0);
    side[2] = unit.dot(p2 - a0);
    error = 1e-9 * scale * std::max(1.0, std::sqrt(e1.squaredNorm() * e2.squaredNorm()) / length);
    return std::isfinite(error);
}

/// A lower bound on the distance from the segment with plane distances s and t to the plane (0 when
/// it may cross it).
double segmentPlaneGap(double s, double t) { return (s > 0.0) == (t > 0.0) ? std::min(std::abs(s), std::abs(t)) : 0.0; }

/// The largest coordinate magnitude among the six corners.
double magnitudeOf(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1, const Vec3 &b2)
{
    double scale = 0.0;
    for (const Vec3 *v : {&a0, &a1, &a2, &b0, &b1, &b2})
        scale = std::max(scale, v->cwiseAbs().maxCoeff());
    return scale;
}

/// A's vertices' signed distances from B's plane and B's from A's, each with its error margin
/// (planeDistances, for distances up to `reach` beyond the corners' magnitude `scale`).
struct FacingPlanes
{
    double fromB[3], fromA[3];
    double errorB = 0.0, errorA = 0.0;
};

bool facingPlanes(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1, const Vec3 &b2,
                  double scale, double reach, FacingPlanes &out)
{
    return planeDistances(b0, b1, b2, a0, a1, a2, scale + reach, out.fromB, out.errorB) &&
           planeDistances(a0, a1, a2, b0, b1, b2, scale + reach, out.fromA, out.errorA);
}

/// The squared distances of the vertex-to-triangle and edge-to-edge features that the planes do
/// not put beyond `limit` go to `visit`, vertices first. `limit` is read before each feature, so a
/// visitor that lowers it culls the rest; a visitor returning true stops the walk (and the walk
/// returns true). A skipped feature's true distance exceeds `limit` by more than any rounding, so
/// its computed value does too.
template <class Visit>
bool visitFeaturesWithin(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1, const Vec3 &b2,
                         const FacingPlanes &planes, const double &limit, Visit &&visit)
{
    const Vec3 *a[3] = {&a0, &a1, &a2}, *b[3] = {&b0, &b1, &b2};
    for (int i = 0; i < 3; ++i)
    {
        if (std::abs(planes.fromB[i]) - planes.errorB <= limit &&
            visit((*a[i] - closestPointOnTriangle(*a[i], b0, b1, b2)).squaredNorm()))
            return true;
        if (std::abs(planes.fromA[i]) - planes.errorA <= limit &&
            visit((*b[i] - closestPointOnTriangle(*b[i], a0, a1, a2)).squaredNorm()))
            return true;
    }
    for (int i = 0; i < 3; ++i)
    {
        const double gapA = segmentPlaneGap(planes.fromB[i], planes.fromB[(i + 1) % 3]) - planes.errorB;
        for (int j = 0; j < 3; ++j)
            if (std::max(gapA, segmentPlaneGap(planes.fromA[j], planes.fromA[(j + 1) % 3]) - planes.errorA) <= limit &&
                visit(segmentSegmentDistanceSquared(*a[i], *a[(i + 1) % 3], *b[j], *b[(j + 1) % 3])))
                return true;
    }
    return false;
}
}  // namespace

double disjointTriangleDistanceBelow(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                                     const Vec3 &b2, double best)
{
    const double scale = magnitudeOf(a0, a1, a2, b0, b1, b2);
    // Without a bound yet, a0's distance to B is one: it is among the candidates, and the other
    // fourteen are then culled against it.
    if (best == std::numeric_limits<double>::infinity())
    {
        const double first = std::sqrt((a0 - closestPointOnTriangle(a0, b0, b1, b2)).squaredNorm());
        if (first < std::numeric_limits<double>::infinity())
            best = first;  // (not when non-finite: the full minimum below decides then)
    }
    FacingPlanes planes;
    if (!(best < std::numeric_limits<double>::infinity()) || !facingPlanes(a0, a1, a2, b0, b1, b2, scale, best, planes))
        return std::min(best, disjointTriangleDistance(a0, a1, a2, b0, b1, b2));
    // Features beyond the best kept so far are skipped: the minimum is the same number.
    double limit = best;
    double bestSquared = std::numeric_limits<double>::infinity();
    visitFeaturesWithin(a0, a1, a2, b0, b1, b2, planes, limit, [&](double squared) {
        if (squared < bestSquared)
        {
            bestSquared = squared;
            limit = std::min(limit, std::sqrt(squared));
        }
        return false;
    });
    return std::min(best, std::sqrt(bestSquared));
}

bool trianglesWithinDistance(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                             const Vec3 &b2, double bound)
{
    // 1. Either triangle's plane separating the other by more than the bound. triangleDistance's
    //    own value may fall below the true distance by a few ulps of the coordinates, so the gap
    //    must clear the bound by that much too for the answers to agree.
    const double gap = std::max(planeGap(a0, a1, a2, b0, b1, b2), planeGap(b0, b1, b2, a0, a1, a2));
    const double scale = magnitudeOf(a0, a1, a2, b0, b1, b2);
    if (gap > bound && gap - 64.0 * std::numeric_limits<double>::epsilon() * scale > bound)
        return false;
    // 2. Two points of the triangles within the bound (the vertex and edge distances are distances
    //    between points of the triangles, so never below the true one): the first feature within
    //    it decides, and features the planes put beyond it are skipped.
    const auto within = [bound](double squared) { return std::sqrt(squared) <= bound; };
    FacingPlanes planes;
    const bool culled = bound >= 0.0 && facingPlanes(a0, a1, a2, b0, b1, b2, scale, bound, planes);
    if (culled ? visitFeaturesWithin(a0, a1, a2, b0, b1, b2, planes, bound, within)
               : within(disjointTriangleDistanceSquared(a0, a1, a2, b0, b1, b2)))
        return true;
    // 3. Otherwise only an intersection (distance 0) puts them within; none is possible when one
    //    triangle lies certainly on one side of the other's plane (a positive gap, as orient3d has it).
    return bound >= 0.0 && !(gap > 0.0) && trianglesIntersect(a0, a1, a2, b0, b1, b2);
}
}  // namespace hcd
