// SPDX-License-Identifier: BSD-3-Clause
// A C-tree node volume (seed §3.3): a sphere or a convex polyhedron (an oriented box), whichever
// bounds the node's content with the smaller volume, and the tests for every pair of kinds.
#pragma once

#include "hybridcd/bv/obb.h"
#include "hybridcd/bv/sphere.h"

#include <vector>

namespace hcd
{
struct CTreeVolume
{
    enum class Kind
    {
        Sphere,
        Box
    };
    Kind kind = Kind::Sphere;
    Sphere sphere;  ///< valid when kind == Sphere
    Obb box;        ///< valid when kind == Box

    /// Fits both (Sphere::fit, Obb::fit) and keeps the one of smaller volume (the box on a tie).
    static CTreeVolume fit(const std::vector<Vec3> &points);

    const Vec3 &center() const { return kind == Kind::Sphere ? sphere.center : box.center; }
    /// Radius of a ball about center() that holds the volume.
    double boundingRadius() const;
    double volume() const { return kind == Kind::Sphere ? sphere.volume() : box.volume(); }
    CTreeVolume transformed(const RigidTransform &pose) const;
};

/// Distance between a ball and a box (0 when they meet), exact up to rounding: the ball's centre
/// against its closest point of the box, in the box's frame.
double sphereBoxDistance(const Sphere &s, const Obb &b);

/// True unless the volumes are more than `tolerance` apart: spheres by their centres, boxes by 15
/// separating axes, a sphere and a box by the exact distance. Conservative for every pair.
bool ctreeVolumesOverlap(const CTreeVolume &a, const CTreeVolume &b, double tolerance);

/// A lower bound on the distance between anything the two volumes contain, less `tolerance`,
/// never below zero.
double ctreeDistanceLowerBound(const CTreeVolume &a, const CTreeVolume &b, double tolerance);
}  // namespace hcd
