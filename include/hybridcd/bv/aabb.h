// SPDX-License-Identifier: BSD-3-Clause
// Axis-aligned boxes: dynamic ones, re-boxed in the world frame for every robot pose (seed §3.4).
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <vector>

namespace hcd
{
/// Box {p : |p - center| <= halfExtents componentwise}, axis-aligned in its own frame.
struct Aabb
{
    Vec3 center = Vec3::Zero();
    Vec3 halfExtents = Vec3::Zero();

    double volume() const { return 8.0 * halfExtents.prod(); }

    /// The tight box of `points`, its extents grown by 1e-9 of the coordinates' magnitude so
    /// rounding leaves no point outside. `points` must not be empty.
    static Aabb fit(const std::vector<Vec3> &points);

    /// True when `p` lies in the box (inclusive).
    bool contains(const Vec3 &p) const { return ((p - center).cwiseAbs().array() <= halfExtents.array()).all(); }

    /// The smallest axis-aligned box around this box mapped by `pose` (the dynamic update: the
    /// rotated box is boxed again, |R| times the extents), grown by a relative 1e-12 for rounding.
    Aabb transformed(const RigidTransform &pose) const;
};

/// True unless some axis separates the boxes by more than `tolerance`.
bool aabbsOverlap(const Aabb &a, const Aabb &b, double tolerance);

/// The Euclidean distance between the boxes less `tolerance`, never below zero.
double aabbDistanceLowerBound(const Aabb &a, const Aabb &b, double tolerance);
}  // namespace hcd
