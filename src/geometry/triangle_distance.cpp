// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/geometry/triangle_distance.h"

#include "hybridcd/geometry/triangle_features.h"
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
            // The lines' nearest point on the first from cross products, ((q0 - p0) x d2) . n / |n|^2
            // with n = d1 x d2: Ericson's (b f - c e) / (a e - b^2) by Lagrange's identity, without
            // the cancellation that loses it for nearly parallel segments (triangle_features.cpp).
            const double b = d1.dot(d2);
            const Vec3 n = d1.cross(d2);
            const double denom = n.squaredNorm();
            s = denom > 0.0 ? std::clamp((-r).cross(d2).dot(n) / denom, 0.0, 1.0) : 0.0;
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

double triangleDistance(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1, const Vec3 &b2)
{
    if (trianglesIntersect(a0, a1, a2, b0, b1, b2))
        return 0.0;
    return std::sqrt(triangleFeaturesSquaredReference(a0, a1, a2, b0, b1, b2));
}

double disjointTriangleDistance(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                                const Vec3 &b2)
{
    return std::sqrt(triangleFeaturesSquaredReference(a0, a1, a2, b0, b1, b2));
}

namespace
{
/// The largest coordinate magnitude among the six corners.
double magnitudeOf(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1, const Vec3 &b2)
{
    double scale = 0.0;
    for (const Vec3 *v : {&a0, &a1, &a2, &b0, &b1, &b2})
        scale = std::max(scale, v->cwiseAbs().maxCoeff());
    return scale;
}

/// Whether the two triangles' axis-aligned bounding boxes are apart along some axis (touching
/// boxes are not apart), which rules out any common point.
bool boxesApart(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1, const Vec3 &b2)
{
    for (int k = 0; k < 3; ++k)
        if (std::max({a0[k], a1[k], a2[k]}) < std::min({b0[k], b1[k], b2[k]}) ||
            std::max({b0[k], b1[k], b2[k]}) < std::min({a0[k], a1[k], a2[k]}))
            return true;
    return false;
}
}  // namespace

double disjointTriangleDistanceBelow(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                                     const Vec3 &b2, double best)
{
    // All fifteen features at once in lanes cost less than culling them one by one against the
    // triangles' planes did, and less than a plane test that skips the pair (bench/README.md,
    // section 1, "Triangle pairs in lanes").
    return std::min(best, std::sqrt(triangleFeaturesSquared(a0, a1, a2, b0, b1, b2)));
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
    // 2. The least of the vertex and edge distances (distances between points of the triangles, so
    //    never below the true one) within the bound.
    if (std::sqrt(triangleFeaturesSquared(a0, a1, a2, b0, b1, b2)) <= bound)
        return true;
    // 3. Otherwise only an intersection (distance 0) puts them within; none is possible when one
    //    triangle lies certainly on one side of the other's plane (a positive gap, as orient3d has it),
    //    nor when their bounding boxes are apart along an axis (exact comparisons of coordinates).
    return bound >= 0.0 && !(gap > 0.0) && !boxesApart(a0, a1, a2, b0, b1, b2) &&
           trianglesIntersect(a0, a1, a2, b0, b1, b2);
}
}  // namespace hcd
