// SPDX-License-Identifier: BSD-3-Clause
// GJK distance between two convex bodies given by support mappings, with a verified answer.
//
// GJK (Gilbert, Johnson, Keerthi) walks a simplex of points of the Minkowski difference
// D = A - B towards the origin: v, the point of the simplex closest to the origin, is a point of D,
// so |v| is an upper bound on the distance, and each new support point w of D along -v improves
// the simplex. The same support point also gives a lower bound for free: for the unit u = v / |v|,
//     min over D of u . d = u . (s_A(-u) - s_B(u)) = u . w,
// and the distance is at least that (the plane through the origin's projection separates). So
// every iteration brackets the distance in [u . w, |v|]; the loop stops when the bracket is
// narrower than the requested tolerance, or (intersection test) as soon as the lower bound is
// positive.
//
// Verified verdicts. Support points are exact up to rounding, a few ulps of the coordinates'
// magnitude; the lower bound is therefore reduced by a margin of 1e-12 of the pair's scale
// (|translation| + bounding radius of both bodies) before it is believed. "Separated" is
// reported only when this certified lower bound is positive. "Intersecting" is reported when the
// origin lies in the simplex (a tetrahedron of D's points containing it), or when |v| is within
// the margin of zero (touching up to rounding counts as intersecting). Anything else, i.e. the
// iteration limit reached without either, is "Undecided", which callers treat as intersecting: a
// colliding pair is never reported free.
//
// Numerics. Spheres and capsules run as their cores (a point, a segment) inflated by their radii,
// so that GJK terminates on them as on polytopes. On curved surfaces the simplex's points bunch
// together: the face region's closest point is taken by projection on the triangle's normal
// (accurate on long thin triangles), a tetrahedron flatter than 1e-9 of its longest edge cubed
// never proves containment, and when rounding stops |v| from decreasing the simplex collapses to
// the segment from v to the newest support point (up to 200 times) before the query gives up.
//
// Warm start (review §4.3-4.6): the caller keeps a GjkWarmStart per pair of bodies and passes it
// to the next query; the last direction v seeds the first support point, so that coherent queries
// (successive states of a motion) start next to the answer.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"
#include "hybridcd/geometry/shape.h"

#include <array>

namespace hcd
{
/// A convex body for GJK: a support-mapped shape placed in the world by `worldFromShape`, or the
/// convex hull of one to three world points (a triangle, a segment or a point). Holds a pointer
/// to the shape, which must outlive it.
struct GjkBody
{
    const Shape *shape = nullptr;  ///< null for a point hull
    RigidTransform worldFromShape;
    std::array<Vec3, 3> corners{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};  ///< world, when shape is null
    int cornerCount = 0;
    /// Radius around the core (shape or corners): spheres and capsules are placed as their centre
    /// point or axis segment inflated by their radius. The body is {x : dist(x, core) <= inflation}.
    double inflation = 0.0;
    /// Extra scale of an inflated core (|translation| + bounding radius of the shape).
    double coreScale = 0.0;

    /// The shape placed by `worldFromShape`. Precondition: shape.isSupportMapped().
    static GjkBody placed(const Shape &shape, const RigidTransform &worldFromShape);
    /// The closed triangle (a, b, c), world frame (may be degenerate).
    static GjkBody triangle(const Vec3 &a, const Vec3 &b, const Vec3 &c);
    /// The single world point p.
    static GjkBody point(const Vec3 &p);

    /// World point of the core maximising direction . x (direction in world, any length); the
    /// body's own support point is that plus inflation * direction / |direction|.
    Vec3 support(const Vec3 &direction) const;
    /// A world point of the body (its centre for shapes, the first corner otherwise).
    Vec3 centre() const;
    /// |translation| + bounding radius (world units): the magnitude of the body's coordinates.
    double scale() const;
};

/// Caller-owned coherence cache of one pair of bodies (A, B in that order).
struct GjkWarmStart
{
    /// The last direction v = pointA - pointB (world); zero when there is none yet.
    Vec3 direction = Vec3::Zero();
};

/// What to compute.
struct GjkRequest
{
    /// Stop as soon as the pair is certified separated (the intersection test); otherwise run
    /// until the distance bracket is narrow (the distance query).
    bool stopWhenSeparated = false;
    /// Stop once upperBound - lowerBound <= relativeTolerance * upperBound (+ the rounding margin).
    double relativeTolerance = 1e-10;
    /// Iterations before the query gives up (the bounds then stay valid, only looser).
    int maxIterations = 1000;
};

/// How the verdict was established.
enum class GjkVerdict
{
    Separated,     ///< certified: lowerBound > 0 after the rounding margin
    Intersecting,  ///< the origin is in the simplex, or |v| is within the rounding margin
    Undecided,     ///< neither, within maxIterations or before rounding stalled it: treat as intersecting
};

/// Outcome of gjkDistance; all points in world coordinates, lengths in world units.
struct GjkResult
{
    GjkVerdict verdict = GjkVerdict::Undecided;
    /// Certified lower bound on the distance (>= 0; 0 unless separated).
    double lowerBound = 0.0;
    /// Upper bound: |pointA - pointB| up to rounding (0 when intersecting).
    double upperBound = 0.0;
    /// Points of A and B (convex combinations of support points) at distance upperBound; when
    /// intersecting, the last such pair (near the contact, not a witness).
    Vec3 pointA = Vec3::Zero();
    Vec3 pointB = Vec3::Zero();
    int iterations = 0;

    /// True unless certified separated (Undecided counts as intersecting).
    bool intersecting() const { return verdict != GjkVerdict::Separated; }
};

/// The rounding margin used for the pair (world units): 1e-12 of a.scale() + b.scale().
double gjkMargin(const GjkBody &a, const GjkBody &b);

/// GJK between a and b; `warm` is read for the start and written with the final direction.
GjkResult gjkDistance(const GjkBody &a, const GjkBody &b, const GjkRequest &request, GjkWarmStart &warm);
}  // namespace hcd
