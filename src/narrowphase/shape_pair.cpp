// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/shape_pair.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/narrowphase/convex_piece.h"
#include "hybridcd/narrowphase/linear_program.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace hcd
{
namespace
{
constexpr double kShapeMarginRelative = 1e-12;

using PairFunction = ShapePairResult (*)(const Shape &, const RigidTransform &, const Shape &, const RigidTransform &,
                                         ShapePairQuery, ShapePairScratch &);

double pairScale(const Shape &a, const RigidTransform &worldFromA, const Shape &b, const RigidTransform &worldFromB)
{
    return worldFromA.translation.norm() + boundingRadius(a) + worldFromB.translation.norm() + boundingRadius(b);
}

// A result from a signed gap `gap` (distance when positive) between the points pa and pb.
ShapePairResult fromGap(double gap, double margin, const Vec3 &pa, const Vec3 &pb)
{
    ShapePairResult r;
    r.intersecting = !(gap > margin);
    r.distance = r.intersecting ? 0.0 : gap;
    r.pointA = pa;
    r.pointB = pb;
    return r;
}

// The segment of a capsule (its axis) in world coordinates.
std::array<Vec3, 2> capsuleAxis(const Shape &capsule, const RigidTransform &worldFromCapsule)
{
    const Vec3 half = worldFromCapsule.rotation.col(2) * capsule.halfLength();
    return {worldFromCapsule.translation - half, worldFromCapsule.translation + half};
}

// Points realising the distance between two sets inflated by radii rA and rB around the closest
// points ca (of A's core) and cb (of B's core).
ShapePairResult inflated(const Vec3 &ca, double ra, const Vec3 &cb, double rb, double margin)
{
    const Vec3 d = cb - ca;
    const double length = d.norm();
    const Vec3 u = length > 0.0 ? Vec3(d / length) : Vec3::UnitX();
    return fromGap(length - ra - rb, margin, ca + ra * u, cb - rb * u);
}

// --- Closed forms ------------------------------------------------------------------------------

ShapePairResult sphereSphere(const Shape &a, const RigidTransform &wa, const Shape &b, const RigidTransform &wb,
                             ShapePairQuery, ShapePairScratch &)
{
    return inflated(wa.translation, a.radius(), wb.translation, b.radius(),
                    kShapeMarginRelative * pairScale(a, wa, b, wb));
}

ShapePairResult sphereCapsule(const Shape &a, const RigidTransform &wa, const Shape &b, const RigidTransform &wb,
                              ShapePairQuery, ShapePairScratch &)
{
    const auto axis = capsuleAxis(b, wb);
    Vec3 onSphere, onAxis;
    closestPointsOfSegments(wa.translation, wa.translation, axis[0], axis[1], onSphere, onAxis);
    return inflated(wa.translation, a.radius(), onAxis, b.radius(), kShapeMarginRelative * pairScale(a, wa, b, wb));
}

ShapePairResult capsuleCapsule(const Shape &a, const RigidTransform &wa, const Shape &b, const RigidTransform &wb,
                               ShapePairQuery, ShapePairScratch &)
{
    const auto axisA = capsuleAxis(a, wa), axisB = capsuleAxis(b, wb);
    Vec3 onA, onB;
    closestPointsOfSegments(axisA[0], axisA[1], axisB[0], axisB[1], onA, onB);
    return inflated(onA, a.radius(), onB, b.radius(), kShapeMarginRelative * pairScale(a, wa, b, wb));
}

ShapePairResult sphereBox(const Shape &a, const RigidTransform &wa, const Shape &b, const RigidTransform &wb,
                          ShapePairQuery, ShapePairScratch &)
{
    // The sphere's centre in the box frame, clamped to the box: the box's closest point.
    const Vec3 local = wb.rotation.transpose() * (wa.translation - wb.translation);
    const Vec3 clamped = local.cwiseMax(-b.extents()).cwiseMin(b.extents());
    const double margin = kShapeMarginRelative * pairScale(a, wa, b, wb);
    if (clamped == local)
        return fromGap(-1.0, margin, wa.translation, wa.translation);
    return inflated(wa.translation, a.radius(), wb.apply(clamped), 0.0, margin);
}

ShapePairResult byGjk(const Shape &a, const RigidTransform &wa, const Shape &b, const RigidTransform &wb,
                      ShapePairQuery query, ShapePairScratch &scratch);

// Separating axes for two boxes: face normals of both and the nine edge cross products.
// Cross products of (nearly) parallel edges are skipped, which can only turn "separated" into
// "intersecting" (the face axes decide such pairs up to the skipped axis's tiny gap).
ShapePairResult boxBox(const Shape &a, const RigidTransform &wa, const Shape &b, const RigidTransform &wb,
                       ShapePairQuery query, ShapePairScratch &scratch)
{
    if (query != ShapePairQuery::Intersection)
        return byGjk(a, wa, b, wb, query, scratch);
    const double margin = kShapeMarginRelative * pairScale(a, wa, b, wb);
    const Vec3 t = wb.translation - wa.translation;
    const Mat3 &ra = wa.rotation, &rb = wb.rotation;
    auto gapAlong = [&](const Vec3 &axis) {
        double extentA = 0.0, extentB = 0.0;
        for (int i = 0; i < 3; ++i)
        {
            extentA += a.extents()[i] * std::abs(axis.dot(ra.col(i)));
            extentB += b.extents()[i] * std::abs(axis.dot(rb.col(i)));
        }
        return std::abs(axis.dot(t)) - extentA - extentB;
    };
    bool separated = false;
    for (int i = 0; i < 3 && !separated; ++i)
        separated = gapAlong(ra.col(i)) > margin || gapAlong(rb.col(i)) > margin;
    for (int i = 0; i < 3 && !separated; ++i)
        for (int j = 0; j < 3 && !separated; ++j)
        {
            const Vec3 axis = ra.col(i).cross(rb.col(j));
            const double length = axis.norm();
            if (length > 1e-9)
                separated = gapAlong(axis / length) > margin;
        }
    ShapePairResult r;
    r.intersecting = !separated;
    r.pointA = wa.translation;
    r.pointB = wb.translation;
    if (separated)  // a positive lower bound suffices for Intersection queries
        r.distance = margin;
    return r;
}

// Anything with a support mapping against the half-space b: the support point along -n.
ShapePairResult supportHalfspace(const Shape &a, const RigidTransform &wa, const Shape &b, const RigidTransform &wb,
                                 ShapePairQuery, ShapePairScratch &)
{
    const Vec3 n = wb.rotation * b.normal();
    const double offset = b.offset() + n.dot(wb.translation);
    const Vec3 deepest = wa.apply(supportPoint(a, wa.rotation.transpose() * -n));
    const double gap = n.dot(deepest) - offset;
    const double margin = kShapeMarginRelative *
                          (wa.translation.norm() + boundingRadius(a) + wb.translation.norm() + std::abs(b.offset()));
    return fromGap(gap, margin, deepest, deepest - gap * n);
}

// Two half-spaces meet unless their normals are exactly opposite and the offsets leave a gap.
ShapePairResult halfspaceHalfspace(const Shape &a, const RigidTransform &wa, const Shape &b, const RigidTransform &wb,
                                   ShapePairQuery, ShapePairScratch &)
{
    const Vec3 na = wa.rotation * a.normal(), nb = wb.rotation * b.normal();
    const double oa = a.offset() + na.dot(wa.translation), ob = b.offset() + nb.dot(wb.translation);
    ShapePairResult r;
    r.intersecting = true;
    if (na == -nb)
    {
        // {na.x <= oa} and {na.x >= -ob}: a gap of -ob - oa between the planes when positive.
        const double gap = -ob - oa;
        const double margin =
            kShapeMarginRelative * (wa.translation.norm() + wb.translation.norm() + std::abs(oa) + std::abs(ob));
        const Vec3 onA = na * oa;
        return fromGap(gap, margin, onA, onA + gap * na);
    }
    return r;
}

// World corners of a box or the world points of a convex shape (the polytope kinds).
std::vector<Vec3> worldPolytopePoints(const Shape &shape, const RigidTransform &worldFromShape)
{
    std::vector<Vec3> points = tessellationPoints(shape, 2, TessellationSide::Inner);
    for (Vec3 &p : points)
        p = worldFromShape.apply(p);
    return points;
}

bool isPolytope(const Shape &shape) { return shape.kind() == ShapeKind::Box || shape.kind() == ShapeKind::Convex; }

// GJK between two bodies. An undecided pair is settled by the exact LP when both are polytopes
// (`polytopeA`/`polytopeB` give their world points, made only then), else counted.
template <class PointsA, class PointsB>
ShapePairResult gjkBodies(const GjkBody &ga, const GjkBody &gb, bool polytopes, const PointsA &polytopeA,
                          const PointsB &polytopeB, ShapePairQuery query, ShapePairScratch &scratch)
{
    GjkRequest request;
    request.stopWhenSeparated = query == ShapePairQuery::Intersection;
    if (query == ShapePairQuery::DistanceBound)
        request.relativeTolerance = 1e-2;
    const GjkResult g = gjkDistance(ga, gb, request, scratch.warmStart);
    ++scratch.gjkQueries;
    scratch.gjkIterations += static_cast<std::uint64_t>(g.iterations);
    ShapePairResult r;
    r.pointA = g.pointA;
    r.pointB = g.pointB;
    r.intersecting = g.intersecting();
    r.distance = g.lowerBound;
    if (g.verdict == GjkVerdict::Undecided)
    {
        if (polytopes)
        {
            ++scratch.polytopeFallbacks;
            const IntersectionResult lp =
                intersectConvexPieces(ConvexPiece::hullOf(polytopeA()), ConvexPiece::hullOf(polytopeB()), scratch.lp);
            r.intersecting = lp.intersecting;
            // Disjoint by the LP but below GJK's resolution: a positive distance under the margin.
            r.distance = lp.intersecting ? 0.0 : std::max(-lp.depth, 0.0);
        }
        else
            ++scratch.undecided;
    }
    return r;
}

ShapePairResult byGjk(const Shape &a, const RigidTransform &wa, const Shape &b, const RigidTransform &wb,
                      ShapePairQuery query, ShapePairScratch &scratch)
{
    return gjkBodies(
        GjkBody::placed(a, wa), GjkBody::placed(b, wb), isPolytope(a) && isPolytope(b),
        [&] { return worldPolytopePoints(a, wa); }, [&] { return worldPolytopePoints(b, wb); }, query, scratch);
}

template <PairFunction F>
ShapePairResult swapped(const Shape &a, const RigidTransform &wa, const Shape &b, const RigidTransform &wb,
                        ShapePairQuery query, ShapePairScratch &scratch)
{
    ShapePairResult r = F(b, wb, a, wa, query, scratch);
    std::swap(r.pointA, r.pointB);
    return r;
}

using Table = std::array<std::array<PairFunction, kShapeKindCount>, kShapeKindCount>;

// The table, built once (function-local static, immutable afterwards).
const Table &pairTable()
{
    static const Table table = [] {
        Table t{};
        const int meshIndex = static_cast<int>(ShapeKind::Mesh);
        const int half = static_cast<int>(ShapeKind::Halfspace);
        for (int i = 0; i < kShapeKindCount; ++i)
            for (int j = 0; j < kShapeKindCount; ++j)
                t[i][j] = i == meshIndex || j == meshIndex ? nullptr : byGjk;
        auto set = [&t](ShapeKind a, ShapeKind b, PairFunction f, PairFunction reversed) {
            t[static_cast<int>(a)][static_cast<int>(b)] = f;
            t[static_cast<int>(b)][static_cast<int>(a)] = reversed;
        };
        set(ShapeKind::Sphere, ShapeKind::Sphere, sphereSphere, sphereSphere);
        set(ShapeKind::Sphere, ShapeKind::Capsule, sphereCapsule, swapped<sphereCapsule>);
        set(ShapeKind::Capsule, ShapeKind::Capsule, capsuleCapsule, capsuleCapsule);
        set(ShapeKind::Sphere, ShapeKind::Box, sphereBox, swapped<sphereBox>);
        set(ShapeKind::Box, ShapeKind::Box, boxBox, boxBox);
        for (int i = 0; i < kShapeKindCount; ++i)
            if (i != meshIndex && i != half)
                set(static_cast<ShapeKind>(i), ShapeKind::Halfspace, supportHalfspace, swapped<supportHalfspace>);
        set(ShapeKind::Halfspace, ShapeKind::Halfspace, halfspaceHalfspace, halfspaceHalfspace);
        return t;
    }();
    return table;
}

[[noreturn]] void unsupported(const Shape &a, const Shape &b)
{
    throw std::invalid_argument(std::string("Unsupported shape pair: ") + shapeKindName(a.kind()) + " - " +
                                shapeKindName(b.kind()));
}
}  // namespace

ShapePairResult shapePair(const Shape &a, const RigidTransform &worldFromA, const Shape &b,
                          const RigidTransform &worldFromB, ShapePairQuery query, ShapePairScratch &scratch)
{
    const PairFunction f = pairTable()[static_cast<int>(a.kind())][static_cast<int>(b.kind())];
    if (!f)
        unsupported(a, b);
    return f(a, worldFromA, b, worldFromB, query, scratch);
}

ShapePairResult shapeTriangle(const Shape &a, const RigidTransform &worldFromA, const Vec3 &t0, const Vec3 &t1,
                              const Vec3 &t2, ShapePairQuery query, ShapePairScratch &scratch)
{
    const double scale =
        worldFromA.translation.norm() + boundingRadius(a) + std::max({t0.norm(), t1.norm(), t2.norm()});
    const double margin = kShapeMarginRelative * scale;
    switch (a.kind())
    {
    case ShapeKind::Sphere:
    {
        const Vec3 onTriangle = closestPointOnTriangle(worldFromA.translation, t0, t1, t2);
        return inflated(worldFromA.translation, a.radius(), onTriangle, 0.0, margin);
    }
    case ShapeKind::Capsule:
    {
        const auto axis = capsuleAxis(a, worldFromA);
        if (segmentIntersectsTriangle(axis[0], axis[1], t0, t1, t2))  // exact
        {
            ShapePairResult r;
            r.intersecting = true;
            r.pointA = r.pointB = axis[0];
            return r;
        }
        // Disjoint segment and triangle: the closest pair involves an end point or an edge.
        Vec3 bestAxis = axis[0], bestTriangle = closestPointOnTriangle(axis[0], t0, t1, t2);
        auto consider = [&](const Vec3 &p, const Vec3 &q) {
            if ((p - q).squaredNorm() < (bestAxis - bestTriangle).squaredNorm())
            {
                bestAxis = p;
                bestTriangle = q;
            }
        };
        consider(axis[1], closestPointOnTriangle(axis[1], t0, t1, t2));
        const std::array<Vec3, 3> corners{t0, t1, t2};
        for (int k = 0; k < 3; ++k)
        {
            Vec3 onAxis, onEdge;
            closestPointsOfSegments(axis[0], axis[1], corners[k], corners[(k + 1) % 3], onAxis, onEdge);
            consider(onAxis, onEdge);
        }
        return inflated(bestAxis, a.radius(), bestTriangle, 0.0, margin);
    }
    case ShapeKind::Halfspace:
    {
        const Vec3 n = worldFromA.rotation * a.normal();
        const double offset = a.offset() + n.dot(worldFromA.translation);
        const std::array<Vec3, 3> corners{t0, t1, t2};
        int lowest = 0;
        for (int k = 1; k < 3; ++k)
            if (n.dot(corners[k]) < n.dot(corners[lowest]))
                lowest = k;
        const double gap = n.dot(corners[lowest]) - offset;
        return fromGap(gap, kShapeMarginRelative * (scale + std::abs(a.offset())), corners[lowest] - gap * n,
                       corners[lowest]);
    }
    case ShapeKind::Mesh:
        throw std::invalid_argument("Unsupported shape pair: mesh - triangle");
    default:
        break;
    }
    return gjkBodies(
        GjkBody::placed(a, worldFromA), GjkBody::triangle(t0, t1, t2), isPolytope(a),
        [&] { return worldPolytopePoints(a, worldFromA); },
        [&] {
            return std::vector<Vec3>{t0, t1, t2};
        },
        query, scratch);
}
}  // namespace hcd
