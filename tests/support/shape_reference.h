// SPDX-License-Identifier: BSD-3-Clause
// Independent references for shape queries: every compact shape bracketed between an inner and
// an outer polytope (geometry/shape.h tessellationPoints, with their stated error), decided by the
// LP narrow phase (linear_program.h), which shares no code with GJK or the closed forms. Inner
// hulls intersecting => the shapes intersect; outer hulls disjoint => the shapes are disjoint;
// otherwise the reference does not know and the case is skipped (and counted).
#pragma once

#include "hybridcd/geometry/shape.h"
#include "hybridcd/narrowphase/convex_piece.h"
#include "hybridcd/narrowphase/linear_program.h"
#include "support/test_support.h"

#include <algorithm>
#include <random>
#include <vector>

namespace hcd::test
{
/// The compact convex kinds (support-mapped).
inline const std::vector<ShapeKind> &compactKinds()
{
    static const std::vector<ShapeKind> kinds{ShapeKind::Sphere,   ShapeKind::Box,  ShapeKind::Capsule,
                                              ShapeKind::Cylinder, ShapeKind::Cone, ShapeKind::Ellipsoid,
                                              ShapeKind::Convex};
    return kinds;
}

/// A random shape of `kind`, every length in [0.3, 1] times `scale`; a convex shape is 12 random
/// points of the ball of radius `scale`; a half-space has a random unit normal and offset 0.
inline Shape randomShape(ShapeKind kind, TestRandom &rng, double scale = 1.0)
{
    std::uniform_real_distribution<double> length(0.3 * scale, scale);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    switch (kind)
    {
    case ShapeKind::Sphere:
        return Shape::sphere(length(rng));
    case ShapeKind::Box:
        return Shape::box(Vec3(length(rng), length(rng), length(rng)));
    case ShapeKind::Capsule:
        return Shape::capsule(0.6 * length(rng), 0.6 * length(rng));
    case ShapeKind::Cylinder:
        return Shape::cylinder(length(rng), length(rng));
    case ShapeKind::Cone:
        return Shape::cone(length(rng), length(rng));
    case ShapeKind::Ellipsoid:
        return Shape::ellipsoid(Vec3(length(rng), length(rng), length(rng)));
    case ShapeKind::Halfspace:
        return Shape::halfspace(Vec3(u(rng), u(rng), u(rng)) + Vec3(0.0, 0.0, 1e-3), 0.0);
    case ShapeKind::Convex:
    {
        std::vector<Vec3> points;
        while (points.size() < 12)
        {
            const Vec3 p(u(rng), u(rng), u(rng));
            if (p.squaredNorm() <= 1.0)
                points.push_back(p * scale);
        }
        return Shape::convex(points);
    }
    case ShapeKind::Mesh:
        break;
    }
    return Shape::sphere(scale);
}

/// Inner and outer hulls of a compact shape in its own frame.
struct ShapeHulls
{
    ConvexPiece inner;
    ConvexPiece outer;
    std::vector<Vec3> innerPoints;
    std::vector<Vec3> outerPoints;
};

inline ShapeHulls hullsOf(const Shape &shape, int resolution)
{
    ShapeHulls h;
    h.innerPoints = tessellationPoints(shape, resolution, TessellationSide::Inner);
    h.outerPoints = tessellationPoints(shape, resolution, TessellationSide::Outer);
    h.inner = ConvexPiece::hullOf(h.innerPoints);
    h.outer = ConvexPiece::hullOf(h.outerPoints);
    return h;
}

/// What the reference knows about a pair.
enum class Reference
{
    Intersecting,
    Disjoint,
    Unknown,
};

/// The LP on the placed inner hulls and on the placed outer hulls.
inline Reference referenceVerdict(const ShapeHulls &a, const RigidTransform &worldFromA, const ShapeHulls &b,
                                  const RigidTransform &worldFromB, LpWorkspace &lp)
{
    if (intersectConvexPieces(a.inner.transformed(worldFromA), b.inner.transformed(worldFromB), lp).intersecting)
        return Reference::Intersecting;
    if (!intersectConvexPieces(a.outer.transformed(worldFromA), b.outer.transformed(worldFromB), lp).intersecting)
        return Reference::Disjoint;
    return Reference::Unknown;
}

/// The half-space {n.x <= offset} placed by worldFromH against the placed hulls of a shape.
inline Reference referenceHalfspace(const ShapeHulls &a, const RigidTransform &worldFromA, const Shape &halfspace,
                                    const RigidTransform &worldFromH)
{
    const Vec3 n = worldFromH.rotation * halfspace.normal();
    const double offset = halfspace.offset() + n.dot(worldFromH.translation);
    auto lowest = [&](const std::vector<Vec3> &points) {
        double m = std::numeric_limits<double>::infinity();
        for (const Vec3 &p : points)
            m = std::min(m, n.dot(worldFromA.apply(p)));
        return m;
    };
    if (lowest(a.innerPoints) <= offset)
        return Reference::Intersecting;
    if (lowest(a.outerPoints) > offset)
        return Reference::Disjoint;
    return Reference::Unknown;
}

/// The mean half-width of a compact shape over the six axis directions (its typical radius).
inline double meanHalfWidth(const Shape &shape)
{
    double sum = 0.0;
    for (int i = 0; i < 3; ++i)
        for (double sign : {-1.0, 1.0})
        {
            const Vec3 axis = sign * Vec3::Unit(i);
            sum += axis.dot(supportPoint(shape, axis));
        }
    return sum / 6.0;
}

/// A random pose: uniform rotation, translation uniform in the ball of radius `spread`.
inline RigidTransform randomPose(TestRandom &rng, double spread)
{
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Vec3 t;
    do
        t = Vec3(u(rng), u(rng), u(rng));
    while (t.squaredNorm() > 1.0);
    return {randomRotation(rng), t * spread};
}
}  // namespace hcd::test
