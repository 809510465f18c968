// SPDX-License-Identifier: BSD-3-Clause
// Fixed-size axis-aligned boxes (seed §3.4): boxes that bound their content under every rotation.
#pragma once

#include "hybridcd/bv/sphere.h"

namespace hcd
{
/// The axis-aligned cube around a node's bounding sphere. A rotation moves the sphere's centre but
/// not its cube's size or orientation, so the box needs no refitting: only its centre is mapped.
/// The price is looseness, largest for long thin content (the seed's remark on fixed boxes).
struct FixedAabb
{
    Vec3 center = Vec3::Zero();
    double halfSide = 0.0;  ///< the bounding sphere's radius

    double volume() const { return 8.0 * halfSide * halfSide * halfSide; }

    /// The cube of Sphere::fit(points).
    static FixedAabb fit(const std::vector<Vec3> &points)
    {
        const Sphere s = Sphere::fit(points);
        return {s.center, s.radius};
    }

    bool contains(const Vec3 &p) const { return ((p - center).cwiseAbs().array() <= halfSide).all(); }

    /// Rotation-invariant: the mapped centre, the same half side.
    FixedAabb transformed(const RigidTransform &pose) const { return {pose.apply(center), halfSide}; }
};

/// True unless some axis separates the cubes by more than `tolerance`.
bool fixedAabbsOverlap(const FixedAabb &a, const FixedAabb &b, double tolerance);

/// The Euclidean distance between the cubes less `tolerance`, never below zero.
double fixedAabbDistanceLowerBound(const FixedAabb &a, const FixedAabb &b, double tolerance);
}  // namespace hcd
