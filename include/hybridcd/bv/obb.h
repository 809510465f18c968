// SPDX-License-Identifier: BSD-3-Clause
// Oriented bounding boxes and the separating-axis overlap test.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <vector>

namespace hcd
{
/// Box {center + axes * u : |u_i| <= halfExtents_i}; the columns of `axes` are orthonormal.
struct Obb
{
    Vec3 center = Vec3::Zero();
    Mat3 axes = Mat3::Identity();
    Vec3 halfExtents = Vec3::Zero();

    double volume() const { return 8.0 * halfExtents.prod(); }

    /// A box around `points` with the given orthonormal axes, its extents grown by a relative
    /// margin (1e-9 of the coordinates' magnitude) so rounding can never leave a point outside.
    static Obb fitWithAxes(const std::vector<Vec3> &points, const Mat3 &axes);

    /// The smaller (by volume) of the principal-axis box of the points' covariance and the
    /// axis-aligned box. Robust to flat and collinear sets (their zero extents are kept).
    static Obb fit(const std::vector<Vec3> &points);

    /// True when `p` lies in the box (inclusive).
    bool contains(const Vec3 &p) const;

    /// The same box mapped by `pose` (its extents are unchanged).
    Obb transformed(const RigidTransform &pose) const
    {
        return {pose.apply(center), pose.rotation * axes, halfExtents};
    }
};

/// Separating-axis test (15 axes) between box `a` mapped into world by `worldFromA` and box `b`
/// given in world. Conservative: it reports disjoint only when some axis separates the boxes by
/// more than `tolerance`, which callers set to cover rounding at their coordinates' magnitude.
bool obbsOverlap(const Obb &a, const RigidTransform &worldFromA, const Obb &b, double tolerance);

/// The same test for two boxes given in one frame.
bool obbsOverlap(const Obb &a, const Obb &b, double tolerance);

/// A lower bound on the distance between box `a` (mapped by `worldFromA`) and box `b`, less
/// `tolerance` and never below zero: the largest of the distance from each box to the other's
/// bounding box in its own frame (the face-axis gaps added in squares), the gap along the axis
/// through the centres, and the gaps along the nine edge-edge axes.
double obbDistanceLowerBound(const Obb &a, const RigidTransform &worldFromA, const Obb &b, double tolerance);

/// The same bound for two boxes given in one frame.
double obbDistanceLowerBound(const Obb &a, const Obb &b, double tolerance);

/// The same bound, or a smaller one that is still at least `enough` (a pruning threshold): the
/// cheaper stages first, and the first that reaches `enough` answers.
double obbDistanceLowerBound(const Obb &a, const Obb &b, double tolerance, double enough);
}  // namespace hcd
