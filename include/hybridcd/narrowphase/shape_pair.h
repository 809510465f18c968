// SPDX-License-Identifier: BSD-3-Clause
// The narrow phase between two placed shapes (non-mesh kinds), and between a shape and a single
// triangle (the building block of shape-mesh queries).
//
// Pairs are dispatched through a [ShapeKind][ShapeKind] table of functions (as Jolt and Coal
// do): each cell holds a closed form where one exists (sphere-sphere, sphere-capsule,
// capsule-capsule, sphere-box, box-box by separating axes, anything against a half-space by the
// support point along -n, half-space against half-space), GJK with verified bounds otherwise
// (gjk.h), and the exact LP of linear_program.h when GJK cannot decide a pair of polytopes (box
// or convex). The lower triangle is the upper one behind an adapter that swaps the pair; cells
// with a mesh are empty and fail loudly (std::invalid_argument "Unsupported shape pair").
//
// Verdicts: touching counts as intersecting, and a pair is reported free only when its distance
// (or GJK's certified lower bound) exceeds a rounding margin of 1e-12 of the pair's scale
// (|translation| + bounding radius of both). Undecided GJK answers count as intersecting.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"
#include "hybridcd/geometry/shape.h"
#include "hybridcd/narrowphase/gjk.h"
#include "hybridcd/narrowphase/small_lp.h"

#include <cstdint>

namespace hcd
{
/// What a pair query computes.
enum class ShapePairQuery
{
    Intersection,  ///< the verdict only (distance and points may be rough; may stop early)
    Distance,      ///< the verdict and the distance, with closest points
    /// The verdict and a certified lower bound on the distance within about 1e-2 of it (GJK stops
    /// early; closed forms stay exact), with the points that gave it: what conservative
    /// advancement steps on.
    DistanceBound,
};

/// Result of a pair query; points in world coordinates, the distance in world units.
struct ShapePairResult
{
    /// True when the closed shapes share a point (touching included, see the file comment).
    bool intersecting = false;
    /// 0 when intersecting; otherwise (Distance queries) the distance, never above the true one
    /// by more than 1e-9 of it, and below it by about 1e-10 relative when GJK converges (a few
    /// 1e-9 after a rounding stall on curved shapes); for Intersection queries a positive lower
    /// bound.
    double distance = 0.0;
    /// Points of A and of B realising `distance` (Distance queries on separated pairs); near the
    /// contact otherwise.
    Vec3 pointA = Vec3::Zero();
    Vec3 pointB = Vec3::Zero();
};

/// Caller-owned scratch of one stream of pair queries: GJK's warm start (one direction, shared by
/// the pairs of the stream, which is what coherent queries of one pair want), the LP workspace of
/// the polytope fallback, and counters.
struct ShapePairScratch
{
    GjkWarmStart warmStart;
    LpWorkspace lp;
    std::uint64_t gjkQueries = 0;         ///< pairs given to GJK
    std::uint64_t gjkIterations = 0;      ///< their iterations
    std::uint64_t undecided = 0;          ///< GJK answers neither certified: reported intersecting
    std::uint64_t polytopeFallbacks = 0;  ///< undecided polytope pairs settled by the LP
};

/// The pair (a placed by worldFromA, b placed by worldFromB). Throws std::invalid_argument for a
/// pair with a mesh ("Unsupported shape pair").
ShapePairResult shapePair(const Shape &a, const RigidTransform &worldFromA, const Shape &b,
                          const RigidTransform &worldFromB, ShapePairQuery query, ShapePairScratch &scratch);

/// The shape a (placed by worldFromA) against the closed triangle (t0, t1, t2), world frame
/// (may be degenerate). pointB is on the triangle. Closed forms for spheres, capsules and
/// half-spaces, GJK (and the LP for boxes and convex shapes when GJK is undecided) otherwise.
/// Throws std::invalid_argument for a mesh.
ShapePairResult shapeTriangle(const Shape &a, const RigidTransform &worldFromA, const Vec3 &t0, const Vec3 &t1,
                              const Vec3 &t2, ShapePairQuery query, ShapePairScratch &scratch);

}  // namespace hcd
