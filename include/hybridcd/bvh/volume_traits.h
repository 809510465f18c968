// SPDX-License-Identifier: BSD-3-Clause
// What a hierarchy needs from a bounding volume: fitting, a split direction, placement and tests.
//
// Each specialisation adapts one volume type. Every test must be conservative: `overlap` may say
// true for disjoint volumes but never false for volumes that share a point (within `tolerance`
// of slack for rounding), and `lowerBound` must never exceed the true distance.
#pragma once

#include "hybridcd/bv/ellipsoid.h"
#include "hybridcd/bv/hybrid_volume.h"
#include "hybridcd/bv/minimum_volume_ellipsoid.h"
#include "hybridcd/bv/obb.h"
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
void appendMappedSphere(ExportMesh &mesh, const Vec3 &center, const Mat3 &linear);
void appendMappedCube(ExportMesh &mesh, const Vec3 &center, const Mat3 &linear);

template <>
struct VolumeTraits<Obb>
{
    static constexpr const char *kName = "OBB";
    static Obb fit(const std::vector<Vec3> &points) { return Obb::fit(points); }
    static Vec3 splitAxis(const Obb &b)
    {
        int longest = 0;
        b.halfExtents.maxCoeff(&longest);
        return b.axes.col(longest);
    }
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
    static Vec3 splitAxis(const Ellipsoid &e)
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
    static Vec3 splitAxis(const Volume &v) { return VolumeTraits<Obb>::splitAxis(v.box); }
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
}  // namespace hcd
