// SPDX-License-Identifier: BSD-3-Clause
// The geometry of one rigid body, any shape kind, and the exact pair queries a scene makes
// between two bodies.
//
// Semantics. Every compact shape kind (sphere ... convex) is a solid. A mesh is a solid where it
// is closed (geometry/solid_components.h decides, by parity, which points lie inside) and only a
// surface where it is open. A half-space is the solid {x : n . x <= offset}. Two bodies intersect
// when these sets share a point; touching counts (up to the rounding margin of the narrow phase,
// narrowphase/shape_pair.h), and a colliding pair is never reported free.
//
// Shape against mesh. The mesh's triangles sit in an axis-aligned box tree in the mesh's frame;
// the shape is placed in that frame (meshFromShape = inverse(worldFromMesh) * worldFromShape),
// its conservative box culls the tree, and the leaves run the exact shape-triangle test. If no
// triangle meets the solid shape, the shape may still lie wholly inside a closed component:
// one point of the shape is tested against the mesh's solids. (A mesh vertex inside the shape
// needs no test of its own: its triangles meet the solid shape.) A half-space meets a mesh
// exactly when some vertex has n . x <= offset.
#pragma once

#include "hybridcd/bv/aabb.h"
#include "hybridcd/geometry/rigid_transform.h"
#include "hybridcd/geometry/shape.h"
#include "hybridcd/narrowphase/shape_pair.h"
#include "hybridcd/query/query_context.h"

#include <memory>

namespace hcd
{
/// The geometry of one body: its shape and what queries need (for meshes, the triangle tree and
/// the solid query). Immutable after construction; share it between threads freely.
class BodyGeometry
{
public:
    /// Builds what queries need: for a mesh, an AABB tree over its triangles (mesh frame) and
    /// the point-in-solid index of its closed components.
    explicit BodyGeometry(Shape shape);

    /// The shape, in the body's frame.
    const Shape &shape() const { return shape_; }

    /// A conservative world box of the body placed by worldFromBody. A half-space gives an
    /// infinite box (centre 0, infinite half-extents).
    Aabb worldBounds(const RigidTransform &worldFromBody) const;

    /// max |p| over the body, body frame (infinity for a half-space).
    double boundingRadius() const { return radius_; }

    /// The mesh index (null unless the shape is a mesh); defined in body_geometry.cpp.
    struct MeshIndex;
    const MeshIndex *meshIndex() const { return mesh_.get(); }

private:
    Shape shape_;
    double radius_ = 0.0;
    std::shared_ptr<const MeshIndex> mesh_;
};

/// Result of a body pair query; points in world coordinates, the distance in world units.
struct BodyPairResult
{
    bool intersecting = false;
    /// 0 when intersecting. bodiesDistance: the distance (never above the true one by more than
    /// 1e-9 of it); bodiesIntersect: a positive lower bound when not intersecting.
    double distance = 0.0;
    /// Points of A and of B at `distance` (bodiesDistance, separated pairs); near the contact or
    /// unspecified otherwise.
    Vec3 pointA = Vec3::Zero();
    Vec3 pointB = Vec3::Zero();
};

/// Exact: touching counts as intersecting. For Mesh-Mesh pairs throw std::invalid_argument (the
/// caller uses the mesh checkers for those). Scratch and counters come from `context`.
BodyPairResult bodiesIntersect(const BodyGeometry &a, const RigidTransform &worldFromA, const BodyGeometry &b,
                               const RigidTransform &worldFromB, QueryContext &context);

/// Distance (0 when intersecting), never more than the true distance by more than 1e-9 relative.
/// Mesh-Mesh pairs throw std::invalid_argument.
BodyPairResult bodiesDistance(const BodyGeometry &a, const RigidTransform &worldFromA, const BodyGeometry &b,
                              const RigidTransform &worldFromB, QueryContext &context);

/// A certified lower bound on the distance (0 when intersecting), within about 1e-2 of it: GJK
/// stops as soon as its bracket is that narrow (closed forms stay exact). What conservative
/// advancement steps on, at a fraction of bodiesDistance's iterations on curved shapes.
BodyPairResult bodiesDistanceBound(const BodyGeometry &a, const RigidTransform &worldFromA, const BodyGeometry &b,
                                   const RigidTransform &worldFromB, QueryContext &context);

/// The narrow-phase scratch and counters of the body queries made with `context`: GJK queries
/// and iterations, GJK answers left undecided (reported intersecting) and polytope pairs settled
/// by the LP. Counters only grow; read them between queries.
const ShapePairScratch &bodyQueryCounters(QueryContext &context);
}  // namespace hcd
