// SPDX-License-Identifier: BSD-3-Clause
// What a hierarchy needs from a bounding volume: fitting, a split direction, placement and tests.
//
// Each specialisation adapts one volume type. Every test must be conservative: `overlap` may say
// true for disjoint volumes but never false for volumes that share a point (within `tolerance`
// of slack for rounding), and `lowerBound` must never exceed the true distance.
#pragma once

#include "hybridcd/bv/aabb.h"
#include "hybridcd/bv/ctree_volume.h"
#include "hybridcd/bv/ellipsoid.h"
#include "hybridcd/bv/fixed_aabb.h"
#include "hybridcd/bv/hybrid_volume.h"
#include "hybridcd/bv/kdop.h"
#include "hybridcd/bv/medial_sphere.h"
#include "hybridcd/bv/minimum_volume_ellipsoid.h"
#include "hybridcd/bv/obb.h"
#include "hybridcd/bv/principal_axis.h"
#include "hybridcd/bv/sphere.h"
#include "hybridcd/bv/swept_sphere.h"
#include "hybridcd/bvh/export_mesh.h"

#include <algorithm>
#include <array>

#include <cmath>
#include <vector>

namespace hcd
{
template <class Volume>
struct VolumeTraits;

/// The unit sphere as a UV mesh mapped by x -> center + linear * x (ellipsoids; boxes use the cube).
/// Polygons (k-DOP faces, counter-clockwise from outside) are appended as triangle fans.
void appendMappedSphere(ExportMesh &mesh, const Vec3 &center, const Mat3 &linear);
void appendMappedCube(ExportMesh &mesh, const Vec3 &center, const Mat3 &linear);
void appendPolygons(ExportMesh &mesh, const std::vector<std::vector<Vec3>> &polygons);

template <>
struct VolumeTraits<Obb>
{
    static constexpr const char *kName = "OBB";
    static Obb fit(const std::vector<Vec3> &points) { return Obb::fit(points); }
    static Vec3 splitAxis(const Obb &b, const std::vector<Vec3> &)
    {
        int longest = 0;
        b.halfExtents.maxCoeff(&longest);
        return b.axes.col(longest);
    }
    /// The box's axes (columns, world frame): the split candidates, along which children are measured.
    static const Mat3 &splitFrame(const Obb &b) { return b.axes; }
    static const Vec3 &center(const Obb &b) { return b.center; }
    static double radius(const Obb &b) { return b.halfExtents.norm() * (1.0 + 1e-12); }
    static double volume(const Obb &b) { return b.volume(); }
    static Obb transformed(const Obb &b, const RigidTransform &pose) { return b.transformed(pose); }
    static bool overlap(const Obb &a, const Obb &b, double tolerance) { return obbsOverlap(a, b, tolerance); }
    static double lowerBound(const Obb &a, const Obb &b, double tolerance)
    {
        return obbDistanceLowerBound(a, b, tolerance);
    }
    static void appendMesh(const Obb &b, ExportMesh &mesh)
    {
        appendMappedCube(mesh, b.center, b.axes * b.halfExtents.asDiagonal());
    }
};

template <>
struct VolumeTraits<Ellipsoid>
{
    static constexpr const char *kName = "ellipsoid";
    static Ellipsoid fit(const std::vector<Vec3> &points) { return fitMinimumVolumeEllipsoid(points).ellipsoid; }
    static Vec3 splitAxis(const Ellipsoid &e, const std::vector<Vec3> &)
    {
        int longest = 0;
        e.semiAxes.maxCoeff(&longest);
        return e.axes.col(longest);
    }
    static const Vec3 &center(const Ellipsoid &e) { return e.center; }
    static double radius(const Ellipsoid &e) { return e.boundingRadius() * (1.0 + 1e-12); }
    static double volume(const Ellipsoid &e) { return e.volume(); }
    static Ellipsoid transformed(const Ellipsoid &e, const RigidTransform &pose) { return e.transformed(pose); }
    static bool overlap(const Ellipsoid &a, const Ellipsoid &b, double tolerance)
    {
        return ellipsoidsOverlap(a, b, tolerance);
    }
    /// The gap along the line of centres: cheap, and a valid bound for any direction.
    static double lowerBound(const Ellipsoid &a, const Ellipsoid &b, double tolerance)
    {
        const Vec3 d = b.center - a.center;
        const double n = d.norm();
        if (!(n > 0.0))
            return 0.0;
        const Vec3 u = d / n;
        return std::max(0.0, n - a.supportRadius(u) - b.supportRadius(u) - tolerance);
    }
    static void appendMesh(const Ellipsoid &e, ExportMesh &mesh)
    {
        appendMappedSphere(mesh, e.center, e.axes * e.semiAxes.asDiagonal());
    }
};

template <bool EllipsoidFirst>
struct VolumeTraits<HybridVolume<EllipsoidFirst>>
{
    using Volume = HybridVolume<EllipsoidFirst>;
    static constexpr const char *kName = EllipsoidFirst ? "hybrid (ellipsoid first)" : "hybrid (OBB first)";
    static Volume fit(const std::vector<Vec3> &points)
    {
        return {VolumeTraits<Obb>::fit(points), VolumeTraits<Ellipsoid>::fit(points)};
    }
    static Vec3 splitAxis(const Volume &v, const std::vector<Vec3> &p)
    {
        return VolumeTraits<Obb>::splitAxis(v.box, p);
    }
    static const Vec3 &center(const Volume &v) { return v.box.center; }
    /// The smaller of the two circumscribed spheres, both taken about the box centre.
    static double radius(const Volume &v)
    {
        return std::min(VolumeTraits<Obb>::radius(v.box),
                        ((v.ellipsoid.center - v.box.center).norm() + v.ellipsoid.boundingRadius()) * (1.0 + 1e-12));
    }
    static double volume(const Volume &v) { return std::min(v.box.volume(), v.ellipsoid.volume()); }
    static Volume transformed(const Volume &v, const RigidTransform &pose)
    {
        return {v.box.transformed(pose), v.ellipsoid.transformed(pose)};
    }
    static bool overlap(const Volume &a, const Volume &b, double tolerance)
    {
        if (EllipsoidFirst)
            return ellipsoidsOverlap(a.ellipsoid, b.ellipsoid, tolerance) && obbsOverlap(a.box, b.box, tolerance);
        return obbsOverlap(a.box, b.box, tolerance) && ellipsoidsOverlap(a.ellipsoid, b.ellipsoid, tolerance);
    }
    static double lowerBound(const Volume &a, const Volume &b, double tolerance)
    {
        return std::max(VolumeTraits<Obb>::lowerBound(a.box, b.box, tolerance),
                        VolumeTraits<Ellipsoid>::lowerBound(a.ellipsoid, b.ellipsoid, tolerance));
    }
    static void appendMesh(const Volume &v, ExportMesh &mesh)
    {
        VolumeTraits<Obb>::appendMesh(v.box, mesh);
        VolumeTraits<Ellipsoid>::appendMesh(v.ellipsoid, mesh);
    }
};

template <>
struct VolumeTraits<Sphere>
{
    static constexpr const char *kName = "sphere";
    static Sphere fit(const std::vector<Vec3> &points) { return Sphere::fit(points); }
    static Vec3 splitAxis(const Sphere &, const std::vector<Vec3> &points) { return principalAxis(points); }
    static const Vec3 &center(const Sphere &s) { return s.center; }
    static double radius(const Sphere &s) { return s.radius; }
    static double volume(const Sphere &s) { return s.volume(); }
    static Sphere transformed(const Sphere &s, const RigidTransform &pose) { return s.transformed(pose); }
    static bool overlap(const Sphere &a, const Sphere &b, double tolerance) { return spheresOverlap(a, b, tolerance); }
    static double lowerBound(const Sphere &a, const Sphere &b, double tolerance)
    {
        return sphereDistanceLowerBound(a, b, tolerance);
    }
    static void appendMesh(const Sphere &s, ExportMesh &mesh)
    {
        appendMappedSphere(mesh, s.center, s.radius * Mat3::Identity());
    }
};

/// Spheres placed on the medial axis (bvh/medial_axis.h moves them there after the build); fitted
/// like `Sphere` until then.
template <>
struct VolumeTraits<MedialSphere>
{
    static constexpr const char *kName = "medial sphere";
    static MedialSphere fit(const std::vector<Vec3> &points) { return {Sphere::fit(points), 0.0}; }
    static Vec3 splitAxis(const MedialSphere &, const std::vector<Vec3> &points) { return principalAxis(points); }
    static const Vec3 &center(const MedialSphere &s) { return s.ball.center; }
    static double radius(const MedialSphere &s) { return s.ball.radius; }
    static double volume(const MedialSphere &s) { return s.ball.volume(); }
    static MedialSphere transformed(const MedialSphere &s, const RigidTransform &pose) { return s.transformed(pose); }
    static bool overlap(const MedialSphere &a, const MedialSphere &b, double tolerance)
    {
        return spheresOverlap(a.ball, b.ball, tolerance);
    }
    static double lowerBound(const MedialSphere &a, const MedialSphere &b, double tolerance)
    {
        return sphereDistanceLowerBound(a.ball, b.ball, tolerance);
    }
    static void appendMesh(const MedialSphere &s, ExportMesh &mesh)
    {
        appendMappedSphere(mesh, s.ball.center, s.ball.radius * Mat3::Identity());
    }
};

/// C-tree nodes: a sphere or an oriented box per node, whichever is smaller (bv/ctree_volume.h).
template <>
struct VolumeTraits<CTreeVolume>
{
    static constexpr const char *kName = "C-tree (sphere or box)";
    static CTreeVolume fit(const std::vector<Vec3> &points) { return CTreeVolume::fit(points); }
    static Vec3 splitAxis(const CTreeVolume &v, const std::vector<Vec3> &points)
    {
        return v.kind == CTreeVolume::Kind::Box ? VolumeTraits<Obb>::splitAxis(v.box, points) : principalAxis(points);
    }
    static const Vec3 &center(const CTreeVolume &v) { return v.center(); }
    static double radius(const CTreeVolume &v) { return v.boundingRadius(); }
    static double volume(const CTreeVolume &v) { return v.volume(); }
    static CTreeVolume transformed(const CTreeVolume &v, const RigidTransform &pose) { return v.transformed(pose); }
    static bool overlap(const CTreeVolume &a, const CTreeVolume &b, double tolerance)
    {
        return ctreeVolumesOverlap(a, b, tolerance);
    }
    static double lowerBound(const CTreeVolume &a, const CTreeVolume &b, double tolerance)
    {
        return ctreeDistanceLowerBound(a, b, tolerance);
    }
    static void appendMesh(const CTreeVolume &v, ExportMesh &mesh)
    {
        if (v.kind == CTreeVolume::Kind::Box)
            VolumeTraits<Obb>::appendMesh(v.box, mesh);
        else
            appendMappedSphere(mesh, v.sphere.center, v.sphere.radius * Mat3::Identity());
    }
};

/// Dynamic boxes: robot boxes are boxed again in the world frame for each pose.
template <>
struct VolumeTraits<Aabb>
{
    static constexpr const char *kName = "AABB";
    static Aabb fit(const std::vector<Vec3> &points) { return Aabb::fit(points); }
    static Vec3 splitAxis(const Aabb &, const std::vector<Vec3> &points) { return principalAxis(points); }
    /// The world axes: the split candidates besides the principal axis, along which children are measured.
    static Mat3 splitFrame(const Aabb &) { return Mat3::Identity(); }
    static const Vec3 &center(const Aabb &b) { return b.center; }
    static double radius(const Aabb &b) { return b.halfExtents.norm() * (1.0 + 1e-12); }
    static double volume(const Aabb &b) { return b.volume(); }
    static Aabb transformed(const Aabb &b, const RigidTransform &pose) { return b.transformed(pose); }
    static bool overlap(const Aabb &a, const Aabb &b, double tolerance) { return aabbsOverlap(a, b, tolerance); }
    static double lowerBound(const Aabb &a, const Aabb &b, double tolerance)
    {
        return aabbDistanceLowerBound(a, b, tolerance);
    }
    static void appendMesh(const Aabb &b, ExportMesh &mesh)
    {
        appendMappedCube(mesh, b.center, b.halfExtents.asDiagonal());
    }
};

/// Fixed-size boxes: the cube of each node's bounding sphere, never refitted.
template <>
struct VolumeTraits<FixedAabb>
{
    static constexpr const char *kName = "fixed AABB";
    static FixedAabb fit(const std::vector<Vec3> &points) { return FixedAabb::fit(points); }
    static Vec3 splitAxis(const FixedAabb &, const std::vector<Vec3> &points) { return principalAxis(points); }
    static const Vec3 &center(const FixedAabb &b) { return b.center; }
    /// The cube's own circumscribed sphere (not the tighter sphere it was made from), so that
    /// the tree tests boxes and not spheres.
    static double radius(const FixedAabb &b) { return std::sqrt(3.0) * b.halfSide * (1.0 + 1e-12); }
    static double volume(const FixedAabb &b) { return b.volume(); }
    static FixedAabb transformed(const FixedAabb &b, const RigidTransform &pose) { return b.transformed(pose); }
    static bool overlap(const FixedAabb &a, const FixedAabb &b, double tolerance)
    {
        return fixedAabbsOverlap(a, b, tolerance);
    }
    static double lowerBound(const FixedAabb &a, const FixedAabb &b, double tolerance)
    {
        return fixedAabbDistanceLowerBound(a, b, tolerance);
    }
    static void appendMesh(const FixedAabb &b, ExportMesh &mesh)
    {
        appendMappedCube(mesh, b.center, b.halfSide * Mat3::Identity());
    }
};

template <int K>
struct VolumeTraits<KDop<K>>
{
    using Volume = KDop<K>;
    static constexpr const char *kName = K == 14 ? "14-DOP" : K == 18 ? "18-DOP" : "26-DOP";
    static Volume fit(const std::vector<Vec3> &points) { return Volume::fit(points); }
    // Built bottom-up by VolumeTree: tight slabs at the leaves, unions above, margins last.
    static Volume tight(const std::vector<Vec3> &points) { return Volume::tight(points); }
    static Volume tightUnion(const Volume &a, const Volume &b) { return Volume::tightUnion(a, b); }
    static Volume withMargin(const Volume &v) { return Volume::withMargin(v); }
    static Vec3 splitAxis(const Volume &, const std::vector<Vec3> &points) { return principalAxis(points); }
    static const Vec3 &center(const Volume &d) { return d.center; }
    /// Half the diagonal of the box slabs, about their centre: the box holds the polytope.
    static double radius(const Volume &d)
    {
        return 0.5 * Vec3(d.hi[0] - d.lo[0], d.hi[1] - d.lo[1], d.hi[2] - d.lo[2]).norm() * (1.0 + 1e-12);
    }
    static double volume(const Volume &d) { return d.volume(); }
    static Volume transformed(const Volume &d, const RigidTransform &pose) { return d.transformed(pose); }
    /// What mapping many volumes by one pose shares (see PlacementOf in query/placed_robot.h).
    using Placement = KDopRotation<K>;
    static Placement placement(const RigidTransform &pose) { return Placement::of(pose); }
    static Volume transformed(const Volume &d, const Placement &mapping) { return d.transformed(mapping); }
    static bool overlap(const Volume &a, const Volume &b, double tolerance) { return kdopsOverlap(a, b, tolerance); }
    static double lowerBound(const Volume &a, const Volume &b, double tolerance)
    {
        return kdopDistanceLowerBound(a, b, tolerance);
    }
    static void appendMesh(const Volume &d, ExportMesh &mesh) { appendPolygons(mesh, d.faces()); }
};

/// Swept-sphere volumes: each node a point, line or rectangle swept sphere (whichever is smallest).
template <>
struct VolumeTraits<Ssv>
{
    static constexpr const char *kName = "swept-sphere";
    static Ssv fit(const std::vector<Vec3> &points) { return Ssv::fit(points); }
    static Vec3 splitAxis(const Ssv &, const std::vector<Vec3> &points) { return principalAxis(points); }
    static const Vec3 &center(const Ssv &s) { return s.center; }
    static double radius(const Ssv &s)
    {
        return (std::hypot(s.halfLength[0], s.halfLength[1]) + s.radius) * (1.0 + 1e-12);
    }
    static double volume(const Ssv &s) { return s.volume(); }
    static Ssv transformed(const Ssv &s, const RigidTransform &pose) { return s.transformed(pose); }
    static bool overlap(const Ssv &a, const Ssv &b, double tolerance) { return ssvsOverlap(a, b, tolerance); }
    static double lowerBound(const Ssv &a, const Ssv &b, double tolerance)
    {
        return ssvDistanceLowerBound(a, b, tolerance);
    }
    /// Drawn as its core's corners' balls and the box around the core thickened by the radius.
    static void appendMesh(const Ssv &s, ExportMesh &mesh)
    {
        if (s.kind == Ssv::Kind::Point)
        {
            appendMappedSphere(mesh, s.center, s.radius * Mat3::Identity());
            return;
        }
        for (const double a : {-1.0, 1.0})
            for (const double b : {-1.0, 1.0})
            {
                appendMappedSphere(mesh, s.center + s.axes * Vec3(a * s.halfLength[0], b * s.halfLength[1], 0.0),
                                   s.radius * Mat3::Identity());
                if (s.kind == Ssv::Kind::Segment)
                    break;
            }
        appendMappedCube(mesh, s.center, s.axes * Vec3(s.halfLength[0], s.halfLength[1], s.radius).asDiagonal());
    }
};
}  // namespace hcd
