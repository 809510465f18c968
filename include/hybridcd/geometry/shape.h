// SPDX-License-Identifier: BSD-3-Clause
// Implicit shapes: spheres, boxes, capsules, cylinders, cones, ellipsoids, half-spaces, convex
// hulls of points and triangle meshes, each in its own frame and centred at its origin.
//
// Every kind but Halfspace and Mesh is a compact convex solid given by its support mapping
// (supportPoint): the point of the shape farthest along a direction. The narrow phase (GJK,
// narrowphase/gjk.h) needs nothing else; the closed forms of narrowphase/shape_pair.h read the
// parameters. Lengths are in the units of the scene (metres in OMPL.app's problems).
#pragma once

#include "hybridcd/geometry/rigid_transform.h"
#include "hybridcd/geometry/triangle_mesh.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hcd
{
/// The kinds of shape. Count is the number of kinds (the dispatch table's size).
enum class ShapeKind
{
    Sphere,
    Box,
    Capsule,
    Cylinder,
    Cone,
    Ellipsoid,
    Halfspace,
    Convex,
    Mesh,
};
constexpr int kShapeKindCount = 9;

/// Lower-case name of a kind ("sphere", "box", ..., "mesh").
const char *shapeKindName(ShapeKind kind);
/// The kind named `name` (as shapeKindName spells it), or nullopt.
std::optional<ShapeKind> shapeKindFromName(const std::string &name);

/// One shape in its own frame. Build it with the named constructors, which validate their
/// parameters (lengths from 1e-100 to 1e100, a half-space's offset within +-1e100, all finite) and
/// throw std::invalid_argument otherwise.
/// Immutable after construction and cheap to copy (point sets and meshes are shared).
class Shape
{
public:
    /// Ball of radius r about the origin.
    static Shape sphere(double radius);
    /// Box {|x_i| <= halfExtents_i}.
    static Shape box(const Vec3 &halfExtents);
    /// Points within `radius` of the segment from (0, 0, -halfLength) to (0, 0, halfLength).
    static Shape capsule(double radius, double halfLength);
    /// Solid cylinder of radius `radius` about local z, from z = -halfLength to z = halfLength.
    static Shape cylinder(double radius, double halfLength);
    /// Solid cone about local z: base disc of radius `baseRadius` at z = -halfHeight, apex at
    /// (0, 0, halfHeight).
    static Shape cone(double baseRadius, double halfHeight);
    /// Ellipsoid {sum (x_i / a_i)^2 <= 1} with semi-axes a = semiAxes along the local axes.
    static Shape ellipsoid(const Vec3 &semiAxes);
    /// The closed half-space {x : n . x <= offset}; `normal` (finite, non-zero) is normalised and
    /// `offset` is divided by its length, so the set is the one given.
    static Shape halfspace(const Vec3 &normal, double offset);
    /// Convex hull of `points` (non-empty, finite; any number, in any order, repeats allowed).
    /// The points are kept as given: the support mapping is the maximum over all of them.
    static Shape convex(std::vector<Vec3> points);
    /// A triangle mesh (non-empty, finite vertices): a solid where it is closed, a surface where
    /// it is open (see query/body_geometry.h).
    static Shape mesh(std::shared_ptr<const TriangleMesh> mesh);

    ShapeKind kind() const { return kind_; }
    /// Sphere, capsule and cylinder radius; the cone's base radius. 0 for other kinds.
    double radius() const { return radius_; }
    /// Capsule and cylinder half-length along z; the cone's half-height. 0 for other kinds.
    double halfLength() const { return halfLength_; }
    /// Box half-extents or ellipsoid semi-axes. Zero for other kinds.
    const Vec3 &extents() const { return extents_; }
    /// Half-space unit normal (zero for other kinds).
    const Vec3 &normal() const { return normal_; }
    /// Half-space offset: the set is {x : normal() . x <= offset()}. 0 for other kinds.
    double offset() const { return offset_; }
    /// The convex kind's points (empty for other kinds).
    const std::vector<Vec3> &points() const;
    /// The mesh kind's mesh (null for other kinds).
    const std::shared_ptr<const TriangleMesh> &meshPointer() const { return mesh_; }

    /// True for the kinds with a support mapping (all but Halfspace and Mesh).
    bool isSupportMapped() const { return kind_ != ShapeKind::Halfspace && kind_ != ShapeKind::Mesh; }

private:
    Shape() = default;
    ShapeKind kind_ = ShapeKind::Sphere;
    double radius_ = 0.0;
    double halfLength_ = 0.0;
    Vec3 extents_ = Vec3::Zero();
    Vec3 normal_ = Vec3::Zero();
    double offset_ = 0.0;
    std::shared_ptr<const std::vector<Vec3>> points_;
    std::shared_ptr<const TriangleMesh> mesh_;
};

/// Support point of a support-mapped shape in its own frame: a point of the shape maximising
/// direction . x (direction in the shape's frame, any length; the zero direction gives some
/// point of the shape). Exact up to rounding (a few ulps of the shape's size).
/// Precondition: shape.isSupportMapped() (otherwise std::invalid_argument).
Vec3 supportPoint(const Shape &shape, const Vec3 &direction);

/// max |p| over the shape, in its own frame: infinity for a half-space.
double boundingRadius(const Shape &shape);

/// A conservative world-frame box [min, max] around the shape placed by `worldFromShape` (grown
/// by a relative 1e-12 for rounding). For a half-space every bound is infinite except, when the
/// world normal is exactly a signed world axis, the one bound that the half-space has on it.
BoundingBox worldBounds(const Shape &shape, const RigidTransform &worldFromShape);

/// True when the point p (shape frame) lies in the closed shape, decided in floating point for
/// the closed-form kinds; the convex kind and meshes are not handled here (std::invalid_argument).
bool containsPoint(const Shape &shape, const Vec3 &p);

/// Which side of the shape a tessellation lies on.
enum class TessellationSide
{
    Inner,  ///< every vertex on the surface: the hull of the vertices lies inside the shape
    Outer,  ///< vertices pushed out so that the hull of the vertices contains the shape
};

/// Points whose convex hull approximates a support-mapped shape (shape frame), with a stated
/// error: for Inner, every point is in the shape; for Outer, the hull contains the shape. Curved
/// surfaces are sampled at `resolution` points per quarter turn (at least 2). For spheres,
/// ellipsoids and capsule caps the inner points are a cube-sphere grid whose angular covering
/// radius is alpha <= 2 asin(sqrt(2) / (2 n)) (n = 2 resolution points per cube edge), and the
/// outer points are those scaled by 1 / cos(alpha) (a hull of an alpha-net of the unit sphere
/// contains the ball of radius cos(alpha)); circles use 4 resolution points and 1 / cos(pi / N).
/// Boxes and convex shapes give their points on both sides. For references in tests.
std::vector<Vec3> tessellationPoints(const Shape &shape, int resolution, TessellationSide side);

/// The relative width of the band between the Inner and Outer tessellations at `resolution`:
/// the outer points are the inner ones scaled by at most 1 + this about the shape's axis/centre.
double tessellationRelativeError(int resolution);
}  // namespace hcd
