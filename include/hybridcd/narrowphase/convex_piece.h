// SPDX-License-Identifier: BSD-3-Clause
// Convex pieces for the exact narrow phase: a convex polytope kept both as half-spaces (what the
// linear program needs) and as vertices and edges (what separating planes are checked against).
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <array>
#include <limits>
#include <vector>

namespace hcd
{
/// A convex polytope kept both as half-spaces n_i . x <= d_i (outward unit normals) and as its
/// vertices, all in one frame (the frame and units of the points it was built from).
///
/// Invariants kept by `hullOf`: normals are unit length; every vertex (indeed every input point)
/// satisfies every inequality; the half-spaces describe the hull of the vertices exactly for
/// full-dimensional pieces and, for flat, collinear or single-point input, a zero-thickness slab
/// (or box) whose thickness is the input's own, at most 1e-11 of its coordinates' magnitude.
struct ConvexPiece
{
    /// Outward unit normals n_i, one per half-space.
    std::vector<Vec3> normals;
    /// Offsets d_i: the piece is {x : n_i . x <= d_i for every i}.
    std::vector<double> offsets;
    /// The hull's vertices (a subset of the input points).
    std::vector<Vec3> vertices;
    /// The hull's edges as pairs of indices into `vertices` (none for a single point).
    std::vector<std::array<int, 2>> edges;
    /// Mean of the vertices (an interior point for full-dimensional pieces).
    Vec3 centroid = Vec3::Zero();
    /// Affine dimension of the input: 3, or 2 / 1 / 0 for flat, collinear and single-point sets.
    int dimension = 3;

    /// Convex hull of `points` (Qhull for full-dimensional sets). Flat or degenerate sets still
    /// give a valid piece: for coplanar sets, the 2D hull's edge half-planes within the plane plus
    /// the two half-spaces n.x <= d and -n.x <= -d (zero thickness); for collinear sets, the two
    /// end caps and a zero-width slab pair in each of two directions orthogonal to the line; for a
    /// single point, an axis-aligned zero-size box. Sets count as flat when they are within 1e-11
    /// of their coordinates' magnitude of it. Never NaN.
    /// Precondition: `points` is non-empty and finite (otherwise std::invalid_argument).
    static ConvexPiece hullOf(const std::vector<Vec3> &points);

    /// The same piece mapped by `pose` (planes, vertices and centroid; edges and dimension kept).
    ConvexPiece transformed(const RigidTransform &pose) const;

    /// max_i (n_i . p - d_i): positive is how far `p` violates the worst inequality (in the
    /// piece's units, since normals are unit), zero or negative when `p` is in the piece.
    double maxViolation(const Vec3 &p) const;

    /// The largest absolute vertex coordinate: the scale that relative tolerances refer to.
    double magnitude() const;
};

/// How far the vertices of `a` and `b` stand apart along a direction: with n the unit vector along
/// `direction`, gap = min over b's vertices of n . v - max over a's of n . v (positive: the plane
/// n . x = offset, halfway between, separates the vertices). gap is -infinity for a zero or
/// non-finite direction.
struct VertexGap
{
    Vec3 normal = Vec3::Zero();
    double offset = 0.0;
    double gap = -std::numeric_limits<double>::infinity();
};
VertexGap vertexGapAlong(const Vec3 &direction, const ConvexPiece &a, const ConvexPiece &b);

/// Sets `normal` and `offset` to the plane along `direction` halfway between the vertex
/// projections when they are more than `minimumGap` apart (leaves them as they are otherwise), and
/// says whether it did; `gap`, when given, receives the gap either way.
bool separateAlong(const Vec3 &direction, const ConvexPiece &a, const ConvexPiece &b, double minimumGap, Vec3 &normal,
                   double &offset, double *gap = nullptr);
}  // namespace hcd
