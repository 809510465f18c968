// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/gjk.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hcd
{
namespace
{
constexpr double kGjkMarginRelative = 1e-12;
constexpr int kMaxRestarts = 200;

// The simplex: up to four points w = a - b of the Minkowski difference with their sources.
struct Simplex
{
    std::array<Vec3, 4> w, a, b;
    int size = 0;
};

// Closest point to the origin of a sub-simplex, as barycentric weights over its vertices.
struct Closest
{
    Vec3 point = Vec3::Zero();
    std::array<double, 4> weight{0.0, 0.0, 0.0, 0.0};
};

Closest closestOnSegment(const Vec3 &p, const Vec3 &q)
{
    Closest c;
    const Vec3 d = q - p;
    const double dd = d.squaredNorm();
    double t = dd > 0.0 ? std::clamp(-p.dot(d) / dd, 0.0, 1.0) : 0.0;
    c.point = p + t * d;
    c.weight = {1.0 - t, t, 0.0, 0.0};
    return c;
}

// Ericson's Voronoi-region walk (Real-Time Collision Detection 5.1.5) for the origin, with the
// weights; a degenerate triangle that reaches the face region falls back to its edges.
Closest closestOnTriangle(const Vec3 &a, const Vec3 &b, const Vec3 &c)
{
    Closest r;
    const Vec3 ab = b - a, ac = c - a;
    const double d1 = -ab.dot(a), d2 = -ac.dot(a);
    if (d1 <= 0.0 && d2 <= 0.0)
    {
        r.point = a;
        r.weight = {1.0, 0.0, 0.0, 0.0};
        return r;
    }
    const double d3 = -ab.dot(b), d4 = -ac.dot(b);
    if (d3 >= 0.0 && d4 <= d3)
    {
        r.point = b;
        r.weight = {0.0, 1.0, 0.0, 0.0};
        return r;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
    {
        const double v = d1 / (d1 - d3);
        r.point = a + v * ab;
        r.weight = {1.0 - v, v, 0.0, 0.0};
        return r;
    }
    const double d5 = -ab.dot(c), d6 = -ac.dot(c);
    if (d6 >= 0.0 && d5 <= d6)
    {
        r.point = c;
        r.weight = {0.0, 0.0, 1.0, 0.0};
        return r;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
    {
        const double w = d2 / (d2 - d6);
        r.point = a + w * ac;
        r.weight = {1.0 - w, 0.0, w, 0.0};
        return r;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        r.point = b + w * (c - b);
        r.weight = {0.0, 1.0 - w, w, 0.0};
        return r;
    }
    const double sum = va + vb + vc;
    if (sum > 0.0 && std::isfinite(sum))
    {
        // Face region: the origin's projection on the plane, from the normal (a cross product of
        // edges keeps its relative accuracy on long thin triangles, where the region tests'
        // products of dot products lose theirs), and the weights from sub-triangle areas.
        const Vec3 n = ab.cross(ac);
        const double nn = n.squaredNorm();
        if (nn > 0.0)
        {
            const Vec3 p = n * (n.dot(a) / nn);
            const double wa = (b - p).cross(c - p).dot(n) / nn, wb = (c - p).cross(a - p).dot(n) / nn;
            const double wc = 1.0 - wa - wb;
            if (wa >= 0.0 && wb >= 0.0 && wc >= 0.0)
            {
                r.point = p;
                r.weight = {wa, wb, wc, 0.0};
                return r;
            }
        }
        const double v = vb / sum, w = vc / sum;
        r.point = a + v * ab + w * ac;
        r.weight = {1.0 - v - w, v, w, 0.0};
        return r;
    }
    // Degenerate (collinear) triangle: the best of its edges.
    const std::array<std::array<int, 2>, 3> edges{{{0, 1}, {1, 2}, {0, 2}}};
    const std::array<Vec3, 3> v{a, b, c};
    double best = std::numeric_limits<double>::infinity();
    for (const auto &e : edges)
    {
        const Closest s = closestOnSegment(v[e[0]], v[e[1]]);
        if (s.point.squaredNorm() < best)
        {
            best = s.point.squaredNorm();
            r = Closest{};
            r.point = s.point;
            r.weight[e[0]] = s.weight[0];
            r.weight[e[1]] = s.weight[1];
        }
    }
    return r;
}

// Closest point of the simplex's hull to the origin; `contained` when the origin is inside a
// (non-degenerate) tetrahedron. The simplex is reduced to the vertices with positive weight.
Vec3 reduceSimplex(Simplex &s, bool &contained)
{
    contained = false;
    Closest c;
    if (s.size == 1)
    {
        c.point = s.w[0];
        c.weight[0] = 1.0;
    }
    else if (s.size == 2)
        c = closestOnSegment(s.w[0], s.w[1]);
    else if (s.size == 3)
        c = closestOnTriangle(s.w[0], s.w[1], s.w[2]);
    else
    {
        // A face is a candidate when the origin is not strictly on the side of the opposite vertex.
        // A flat tetrahedron (6 volume below 1e-9 of its longest edge cubed: four support points
        // of a curved surface, close together) leaves those signs to rounding, so then every face
        // is a candidate and containment is never concluded.
        const std::array<std::array<int, 4>, 4> faces{{{1, 2, 3, 0}, {0, 2, 3, 1}, {0, 1, 3, 2}, {0, 1, 2, 3}}};
        double longest = 0.0;
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j)
                longest = std::max(longest, (s.w[i] - s.w[j]).norm());
        const double volume6 = std::abs((s.w[1] - s.w[0]).cross(s.w[2] - s.w[0]).dot(s.w[3] - s.w[0]));
        const bool flat = !(volume6 > 1e-9 * longest * longest * longest);
        bool anyCandidate = false;
        double best = std::numeric_limits<double>::infinity();
        for (const auto &f : faces)
        {
            const Vec3 &p = s.w[f[0]], &q = s.w[f[1]], &r = s.w[f[2]], &opposite = s.w[f[3]];
            const Vec3 n = (q - p).cross(r - p);
            const double originSide = -n.dot(p), vertexSide = n.dot(opposite - p);
            if (!flat && originSide * vertexSide > 0.0)
                continue;
            anyCandidate = true;
            const Closest t = closestOnTriangle(p, q, r);
            if (t.point.squaredNorm() < best)
            {
                best = t.point.squaredNorm();
                c = Closest{};
                c.point = t.point;
                for (int k = 0; k < 3; ++k)
                    c.weight[f[k]] = t.weight[k];
            }
        }
        if (!anyCandidate)
        {
            contained = true;
            return Vec3::Zero();
        }
    }
    Simplex reduced;
    for (int i = 0; i < s.size; ++i)
        if (c.weight[i] > 0.0)
        {
            reduced.w[reduced.size] = s.w[i];
            reduced.a[reduced.size] = s.a[i];
            reduced.b[reduced.size] = s.b[i];
            ++reduced.size;
        }
    if (reduced.size == 0)  // all weights rounded to zero: keep the newest point
    {
        reduced.w[0] = s.w[s.size - 1];
        reduced.a[0] = s.a[s.size - 1];
        reduced.b[0] = s.b[s.size - 1];
        reduced.size = 1;
        c.point = reduced.w[0];
    }
    s = reduced;
    return c.point;
}

// The points of A and B whose difference is v, from the weights of v over the reduced simplex
// (recomputed by least squares over the simplex, which is affinely independent after reduction).
void witnessPoints(const Simplex &s, Vec3 &pointA, Vec3 &pointB)
{
    Closest c;
    if (s.size == 1)
        c.weight[0] = 1.0;
    else if (s.size == 2)
        c = closestOnSegment(s.w[0], s.w[1]);
    else if (s.size == 3)
        c = closestOnTriangle(s.w[0], s.w[1], s.w[2]);
    else
        c.weight = {0.25, 0.25, 0.25, 0.25};
    pointA = Vec3::Zero();
    pointB = Vec3::Zero();
    for (int i = 0; i < s.size; ++i)
    {
        pointA += c.weight[i] * s.a[i];
        pointB += c.weight[i] * s.b[i];
    }
}
}  // namespace

GjkBody GjkBody::placed(const Shape &shape, const RigidTransform &worldFromShape)
{
    if (!shape.isSupportMapped())
        throw std::invalid_argument(std::string("GJK: no support mapping for a ") + shapeKindName(shape.kind()));
    GjkBody body;
    if (shape.kind() == ShapeKind::Sphere || shape.kind() == ShapeKind::Capsule)
    {
        const Vec3 half = worldFromShape.rotation.col(2) * shape.halfLength();
        body.corners = {worldFromShape.translation - half, worldFromShape.translation + half,
                        worldFromShape.translation};
        body.cornerCount = shape.kind() == ShapeKind::Sphere ? 1 : 2;
        if (body.cornerCount == 1)
            body.corners[0] = worldFromShape.translation;
        body.inflation = shape.radius();
        body.coreScale = worldFromShape.translation.norm() + boundingRadius(shape);
        return body;
    }
    body.shape = &shape;
    body.worldFromShape = worldFromShape;
    return body;
}

GjkBody GjkBody::triangle(const Vec3 &a, const Vec3 &b, const Vec3 &c)
{
    GjkBody body;
    body.corners = {a, b, c};
    body.cornerCount = 3;
    return body;
}

GjkBody GjkBody::point(const Vec3 &p)
{
    GjkBody body;
    body.corners = {p, p, p};
    body.cornerCount = 1;
    return body;
}

Vec3 GjkBody::support(const Vec3 &direction) const
{
    if (shape)
    {
        const Vec3 local = worldFromShape.rotation.transpose() * direction;
        return worldFromShape.apply(supportPoint(*shape, local));
    }
    int best = 0;
    for (int i = 1; i < cornerCount; ++i)
        if (direction.dot(corners[i]) > direction.dot(corners[best]))
            best = i;
    return corners[best];
}

Vec3 GjkBody::centre() const
{
    return shape ? worldFromShape.translation : cornerCount == 2 ? Vec3(0.5 * (corners[0] + corners[1])) : corners[0];
}

double GjkBody::scale() const
{
    if (shape)
        return worldFromShape.translation.norm() + boundingRadius(*shape);
    double m = coreScale;
    for (int i = 0; i < cornerCount; ++i)
        m = std::max(m, corners[i].norm());
    return m;
}

double gjkMargin(const GjkBody &a, const GjkBody &b) { return kGjkMarginRelative * (a.scale() + b.scale()); }

GjkResult gjkDistance(const GjkBody &a, const GjkBody &b, const GjkRequest &request, GjkWarmStart &warm)
{
    GjkResult result;
    const double margin = gjkMargin(a, b);
    Vec3 d = warm.direction;
    if (!d.allFinite() || !(d.squaredNorm() > 0.0))
        d = a.centre() - b.centre();
    if (!(d.squaredNorm() > 0.0))
        d = Vec3::UnitX();

    // Spheres and capsules run as their cores (a point, a segment) inflated by their radii:
    // GJK then converges in finitely many steps on them instead of crawling over a curved face.
    const double inflation = a.inflation + b.inflation;
    Simplex simplex;
    simplex.a[0] = a.support(-d);
    simplex.b[0] = b.support(d);
    simplex.w[0] = simplex.a[0] - simplex.b[0];
    simplex.size = 1;
    Vec3 v = simplex.w[0];
    double lower = 0.0;  // certified
    int restarts = 0;
    double upper = v.norm() - inflation;

    for (int iteration = 0; iteration < request.maxIterations; ++iteration)
    {
        result.iterations = iteration + 1;
        const double length = v.norm();
        upper = std::min(upper, length - inflation);
        if (length <= inflation + margin)
        {
            result.verdict = GjkVerdict::Intersecting;
            break;
        }
        const Vec3 u = v / length;
        const Vec3 pa = a.support(-u), pb = b.support(u);
        const Vec3 w = pa - pb;
        lower = std::max(lower, u.dot(w) - inflation - margin);
        if (lower > 0.0 && request.stopWhenSeparated)
        {
            result.verdict = GjkVerdict::Separated;
            break;
        }
        if (upper - lower <= request.relativeTolerance * std::max(upper, 0.0) + margin)
        {
            result.verdict = lower > 0.0 ? GjkVerdict::Separated : GjkVerdict::Intersecting;
            break;
        }
        // A point already in the simplex means no progress is possible in floating point.
        bool repeated = false;
        for (int i = 0; i < simplex.size; ++i)
            repeated = repeated || simplex.w[i] == w;
        if (repeated)
        {
            result.verdict = lower > 0.0 ? GjkVerdict::Separated : GjkVerdict::Undecided;
            break;
        }
        const Simplex before = simplex;
        simplex.w[simplex.size] = w;
        simplex.a[simplex.size] = pa;
        simplex.b[simplex.size] = pb;
        ++simplex.size;
        bool contained = false;
        const Vec3 next = reduceSimplex(simplex, contained);
        if (contained)
        {
            result.verdict = GjkVerdict::Intersecting;
            v = next;
            break;
        }
        // GJK's |v| decreases strictly. When rounding stops that (a flat simplex on a curved
        // face), collapse the simplex to the single point v (with its points of A and B) and the
        // new support point w, a well-conditioned segment that still makes progress; a few
        // times, then stop with the last simplex.
        if (!(next.squaredNorm() < v.squaredNorm()))
        {
            if (restarts < kMaxRestarts)
            {
                ++restarts;
                Vec3 va, vb;
                witnessPoints(before, va, vb);
                simplex.w = {va - vb, w, Vec3::Zero(), Vec3::Zero()};
                simplex.a = {va, pa, Vec3::Zero(), Vec3::Zero()};
                simplex.b = {vb, pb, Vec3::Zero(), Vec3::Zero()};
                simplex.size = 2;
                const Vec3 collapsed = reduceSimplex(simplex, contained);
                if (collapsed.squaredNorm() < v.squaredNorm())
                {
                    v = collapsed;
                    continue;
                }
            }
            simplex = before;
            result.verdict = lower > 0.0 ? GjkVerdict::Separated : GjkVerdict::Undecided;
            break;
        }
        v = next;
        if (iteration + 1 == request.maxIterations)
            result.verdict = lower > 0.0 ? GjkVerdict::Separated : GjkVerdict::Undecided;
    }

    witnessPoints(simplex, result.pointA, result.pointB);
    const double vLength = v.norm();
    if (vLength > 0.0)
    {
        result.pointA -= (a.inflation / vLength) * v;
        result.pointB += (b.inflation / vLength) * v;
    }
    if (result.verdict == GjkVerdict::Separated)
    {
        result.lowerBound = lower;
        result.upperBound = std::max(upper, lower);
        warm.direction = v;
    }
    else
    {
        result.lowerBound = 0.0;
        result.upperBound = 0.0;
        if (result.verdict == GjkVerdict::Intersecting && v.squaredNorm() > 0.0)
            warm.direction = v;
    }
    return result;
}
}  // namespace hcd
