// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bv/swept_sphere.h"

#include "hybridcd/bv/obb.h"
#include "hybridcd/bv/sphere.h"
#include "hybridcd/geometry/triangle_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hcd
{
namespace
{
// The core in world coordinates: its corners (1, 2 or 4, counter-clockwise for a rectangle).
struct Core
{
    Vec3 center, u, v, normal;  // u, v: the half-length vectors; normal: unit, for a rectangle
    double hu = 0.0, hv = 0.0;
    int cornerCount = 1;
    Vec3 corners[4];
};

Core coreOf(const Ssv &s)
{
    Core c;
    c.center = s.center;
    c.hu = s.halfLength[0];
    c.hv = s.halfLength[1];
    c.u = s.axes.col(0) * c.hu;
    c.v = s.axes.col(1) * c.hv;
    c.normal = s.axes.col(2);
    if (s.kind == Ssv::Kind::Point)
        c.corners[0] = s.center;
    else if (s.kind == Ssv::Kind::Segment)
    {
        c.cornerCount = 2;
        c.corners[0] = s.center - c.u;
        c.corners[1] = s.center + c.u;
    }
    else
    {
        c.cornerCount = 4;
        c.corners[0] = s.center - c.u - c.v;
        c.corners[1] = s.center + c.u - c.v;
        c.corners[2] = s.center + c.u + c.v;
        c.corners[3] = s.center - c.u + c.v;
    }
    return c;
}

// Squared distance from `p` to the rectangle core `r` (clamping in its frame).
double pointRectangleSquared(const Vec3 &p, const Core &r, const Ssv &frame)
{
    const Vec3 d = p - r.center;
    const double s = std::clamp(d.dot(frame.axes.col(0)), -r.hu, r.hu);
    const double t = std::clamp(d.dot(frame.axes.col(1)), -r.hv, r.hv);
    return (d - s * frame.axes.col(0) - t * frame.axes.col(1)).squaredNorm();
}

// Whether segment p0p1 crosses the rectangle's plane at a point inside the rectangle.
bool segmentCrossesRectangle(const Vec3 &p0, const Vec3 &p1, const Core &r, const Ssv &frame)
{
    const double d0 = (p0 - r.center).dot(r.normal), d1 = (p1 - r.center).dot(r.normal);
    if ((d0 > 0.0 && d1 > 0.0) || (d0 < 0.0 && d1 < 0.0) || d0 == d1)
        return false;  // same side, or parallel (then the edges and ends decide)
    const Vec3 x = p0 + (d0 / (d0 - d1)) * (p1 - p0) - r.center;
    return std::fabs(x.dot(frame.axes.col(0))) <= r.hu && std::fabs(x.dot(frame.axes.col(1))) <= r.hv;
}

// Squared distance from segment p0p1 to the rectangle core: zero when it crosses the inside;
// otherwise the closest pair has an end of the segment or a point of the rectangle's boundary.
// The cheap cases (ends, crossing) come first, for an early exit below `enough`.
double segmentRectangleSquared(const Vec3 &p0, const Vec3 &p1, const Core &r, const Ssv &frame, double enough)
{
    double best = std::min(pointRectangleSquared(p0, r, frame), pointRectangleSquared(p1, r, frame));
    if (best <= enough)
        return best;
    if (segmentCrossesRectangle(p0, p1, r, frame))
        return 0.0;
    for (int k = 0; k < 4 && best > enough; ++k)
        best = std::min(best, segmentSegmentDistanceSquared(p0, p1, r.corners[k], r.corners[(k + 1) % 4]));
    return best;
}

// Squared distance between the cores, or any value at most `enough` once it is known to be so.
// Disjoint convex cores meet their distance with a boundary point of one of them (for two
// rectangles: a corner against the other rectangle, or two edges), and intersecting ones meet
// where an edge of one crosses or touches the other; so these cases cover all.
double coreDistanceSquared(const Ssv &a, const Ssv &b, double enough)
{
    const Ssv *sa = &a, *sb = &b;
    if (int(sa->kind) > int(sb->kind))
        std::swap(sa, sb);  // sa is the simpler core
    const Core ca = coreOf(*sa), cb = coreOf(*sb);
    if (sb->kind != Ssv::Kind::Rectangle)
    {
        // Point or segment against point or segment.
        const Vec3 &q1 = cb.corners[cb.cornerCount - 1];
        return segmentSegmentDistanceSquared(ca.corners[0], ca.corners[ca.cornerCount - 1], cb.corners[0], q1);
    }
    if (sa->kind == Ssv::Kind::Point)
        return pointRectangleSquared(ca.corners[0], cb, *sb);
    if (sa->kind == Ssv::Kind::Segment)
        return segmentRectangleSquared(ca.corners[0], ca.corners[1], cb, *sb, enough);
    // Two rectangles: corners against the other rectangle, then edges crossing it, then the
    // sixteen edge pairs.
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 4 && best > enough; ++k)
    {
        best = std::min(best, pointRectangleSquared(ca.corners[k], cb, *sb));
        best = std::min(best, pointRectangleSquared(cb.corners[k], ca, *sa));
    }
    if (best <= enough)
        return best;
    for (int k = 0; k < 4; ++k)
        if (segmentCrossesRectangle(ca.corners[k], ca.corners[(k + 1) % 4], cb, *sb) ||
            segmentCrossesRectangle(cb.corners[k], cb.corners[(k + 1) % 4], ca, *sa))
            return 0.0;
    for (int i = 0; i < 4 && best > enough; ++i)
        for (int j = 0; j < 4 && best > enough; ++j)
            best = std::min(best, segmentSegmentDistanceSquared(ca.corners[i], ca.corners[(i + 1) % 4], cb.corners[j],
                                                                cb.corners[(j + 1) % 4]));
    return best;
}

Obb boundingBox(const Ssv &s)
{
    return {s.center, s.axes, Vec3(s.halfLength[0] + s.radius, s.halfLength[1] + s.radius, s.radius)};
}

double magnitudeOf(const std::vector<Vec3> &points)
{
    double magnitude = 0.0;
    for (const Vec3 &p : points)
        magnitude = std::max(magnitude, p.cwiseAbs().maxCoeff());
    return magnitude;
}

// The radius that holds every point for the fitted core: the exact largest distance, grown.
void closeRadius(Ssv &s, const std::vector<Vec3> &points, double magnitude)
{
    double reach = 0.0;
    for (const Vec3 &p : points)
        reach = std::max(reach, s.coreDistance(p));
    s.radius = reach * (1.0 + 1e-12) + 1e-9 * magnitude + 1e-300;
}

// The shortest interval [from, to] of core positions along one axis that comes within slack_i
// of every coordinate x_i: from = min(x + slack), to = max(x - slack). When from > to a single
// position between them does, and the interval collapses to the midpoint.
std::pair<double, double> coreInterval(const std::vector<double> &x, const std::vector<double> &slack)
{
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < x.size(); ++i)
    {
        lo = std::max(lo, x[i] - slack[i]);
        hi = std::min(hi, x[i] + slack[i]);
    }
    const double from = hi, to = lo;
    if (from > to)
        return {0.5 * (from + to), 0.5 * (from + to)};
    return {from, to};
}
}  // namespace

double Ssv::volume() const
{
    const double a = 2.0 * halfLength[0], b = 2.0 * halfLength[1], r = radius;
    return a * b * 2.0 * r + 2.0 * (a + b) * M_PI * r * r / 2.0 + 4.0 / 3.0 * M_PI * r * r * r;
}

double Ssv::coreDistance(const Vec3 &p) const
{
    const Vec3 d = p - center;
    const double s = std::clamp(d.dot(axes.col(0)), -halfLength[0], halfLength[0]);
    const double t = std::clamp(d.dot(axes.col(1)), -halfLength[1], halfLength[1]);
    return (d - s * axes.col(0) - t * axes.col(1)).norm();
}

Ssv Ssv::fitKind(const std::vector<Vec3> &points, Kind kind)
{
    const double magnitude = magnitudeOf(points);
    Ssv s;
    s.kind = kind;
    if (kind == Kind::Point)
    {
        const Sphere ball = Sphere::fit(points);
        s.center = ball.center;
        closeRadius(s, points, magnitude);
        return s;
    }
    // Principal axes (or the world's, when that box is smaller), longest first, right-handed.
    const Obb box = Obb::fit(points);
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int i, int j) { return box.halfExtents[i] > box.halfExtents[j]; });
    Mat3 axes;
    axes.col(0) = box.axes.col(order[0]);
    axes.col(1) = box.axes.col(order[1]);
    axes.col(2) = axes.col(0).cross(axes.col(1)).normalized();
    s.axes = axes;
    const std::size_t n = points.size();
    std::vector<Vec3> local(n);
    for (std::size_t i = 0; i < n; ++i)
        local[i] = axes.transpose() * (points[i] - box.center);

    std::vector<double> x(n), slack(n);
    if (kind == Kind::Segment)
    {
        // The line through the box centre along the longest axis; the radius is the farthest
        // point from it, and each point's allowance along the line is what that radius leaves.
        double r2 = 0.0;
        for (const Vec3 &l : local)
            r2 = std::max(r2, l.y() * l.y() + l.z() * l.z());
        for (std::size_t i = 0; i < n; ++i)
        {
            x[i] = local[i].x();
            slack[i] = std::sqrt(std::max(0.0, r2 - local[i].y() * local[i].y() - local[i].z() * local[i].z()));
        }
        const auto [lo, hi] = coreInterval(x, slack);
        s.center = box.center + axes.col(0) * (0.5 * (lo + hi));
        s.halfLength = {0.5 * (hi - lo), 0.0};
        closeRadius(s, points, magnitude);
        return s;
    }
    // Rectangle in the plane of the two longest axes, the radius half the thickness. A point's
    // allowance within the plane is shared by both axes: all of it on each (the corners then
    // need a larger radius, measured) or 1/sqrt(2) on each (the radius holds); the smaller wins.
    double r2 = 0.0;
    for (const Vec3 &l : local)
        r2 = std::max(r2, l.z() * l.z());
    Ssv best;
    for (const double share : {1.0, std::sqrt(0.5)})
    {
        Ssv candidate = s;
        Vec3 offset = Vec3::Zero();
        for (int axis = 0; axis < 2; ++axis)
        {
            for (std::size_t i = 0; i < n; ++i)
            {
                x[i] = local[i][axis];
                slack[i] = share * std::sqrt(std::max(0.0, r2 - local[i].z() * local[i].z()));
            }
            const auto [lo, hi] = coreInterval(x, slack);
            offset[axis] = 0.5 * (lo + hi);
            candidate.halfLength[axis] = 0.5 * (hi - lo);
        }
        candidate.center = box.center + axes * offset;
        closeRadius(candidate, points, magnitude);
        if (share == 1.0 || candidate.volume() < best.volume())
            best = candidate;
    }
    return best;
}

Ssv Ssv::fit(const std::vector<Vec3> &points)
{
    Ssv best = fitKind(points, Kind::Point);
    for (const Kind kind : {Kind::Segment, Kind::Rectangle})
    {
        const Ssv candidate = fitKind(points, kind);
        if (candidate.volume() < best.volume())
            best = candidate;
    }
    return best;
}

double ssvGap(const Ssv &a, const Ssv &b) { return std::sqrt(coreDistanceSquared(a, b, -1.0)) - a.radius - b.radius; }

bool ssvsOverlap(const Ssv &a, const Ssv &b, double tolerance)
{
    // The line of centres first: each volume's extent along u is |half-length vectors . u| + r.
    const Vec3 d = b.center - a.center;
    const auto extent = [](const Ssv &s, const Vec3 &u) {
        return s.halfLength[0] * std::fabs(s.axes.col(0).dot(u)) + s.halfLength[1] * std::fabs(s.axes.col(1).dot(u)) +
               s.radius;
    };
    const double dn = d.norm();
    if (dn > 0.0 && dn > extent(a, d / dn) + extent(b, d / dn) + tolerance)
        return false;
    // Then the boxes around the volumes (the core's rectangle grown by the radius on every side),
    // whose separating-axis test is far cheaper than the cores' distance.
    if (!obbsOverlap(boundingBox(a), boundingBox(b), tolerance))
        return false;
    const double reach = a.radius + b.radius + tolerance;
    return coreDistanceSquared(a, b, reach * reach) <= reach * reach;
}

double ssvDistanceLowerBound(const Ssv &a, const Ssv &b, double tolerance)
{
    return std::max(0.0, ssvGap(a, b) - tolerance);
}
}  // namespace hcd
