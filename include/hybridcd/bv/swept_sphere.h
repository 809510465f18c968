// SPDX-License-Identifier: BSD-3-Clause
// Swept-sphere volumes (seed §3.7): a ball swept over a point, a segment or a rectangle.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <array>
#include <vector>

namespace hcd
{
/// The set of points within `radius` of the core {center + axes.col(0) s + axes.col(1) t :
/// |s| <= halfLength[0], |t| <= halfLength[1]}. The kind says which core it is: a point (both
/// half-lengths 0, a sphere), a segment (halfLength[1] = 0, a capsule) or a rectangle (FCL's RSS).
/// The columns of `axes` are orthonormal; axes.col(2) is the rectangle's normal.
struct Ssv
{
    enum class Kind
    {
        Point,
        Segment,
        Rectangle,
    };
    Kind kind = Kind::Point;
    Vec3 center = Vec3::Zero();
    Mat3 axes = Mat3::Identity();
    std::array<double, 2> halfLength{0.0, 0.0};
    double radius = 0.0;

    /// Steiner's formula: core area times 2r, perimeter times pi r^2 / 2, plus the ball.
    double volume() const;

    /// Each kind fitted to `points` on their principal axes (the sphere by Sphere::fit), and the
    /// smallest by volume kept. Whatever the core, the radius is the exact largest distance of a
    /// point from it, grown by 1e-9 of the coordinates' magnitude so rounding leaves no point
    /// outside. `points` must not be empty.
    static Ssv fit(const std::vector<Vec3> &points);

    /// The same fit restricted to one kind (for tests and the bench).
    static Ssv fitKind(const std::vector<Vec3> &points, Kind kind);

    /// Distance from `p` to the core (0 on it).
    double coreDistance(const Vec3 &p) const;

    /// True when `p` lies in the volume (inclusive).
    bool contains(const Vec3 &p) const { return coreDistance(p) <= radius; }

    /// The same volume mapped by `pose`.
    Ssv transformed(const RigidTransform &pose) const
    {
        return {kind, pose.apply(center), pose.rotation * axes, halfLength, radius};
    }
};

/// The distance between the two cores less both radii (negative when the volumes overlap deeply).
/// Cores are compared as degenerate triangles by triangleDistance, which is exact about contact
/// and has a relative error of a few ulps of the coordinates' magnitude otherwise.
double ssvGap(const Ssv &a, const Ssv &b);

/// True unless the volumes are more than `tolerance` apart. A slab test along the line of centres
/// and the separating-axis test of the boxes around the two volumes reject most far pairs first;
/// the core distance decides the rest.
bool ssvsOverlap(const Ssv &a, const Ssv &b, double tolerance);

/// ssvGap less `tolerance`, never below zero: a lower bound on the distance between the contents.
double ssvDistanceLowerBound(const Ssv &a, const Ssv &b, double tolerance);
}  // namespace hcd
