// SPDX-License-Identifier: BSD-3-Clause
// Bounding spheres: a near-minimal fit (Ritter's start, then iterative shrinking) and their tests.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <vector>

namespace hcd
{
/// Ball {p : |p - center| <= radius}.
struct Sphere
{
    Vec3 center = Vec3::Zero();
    double radius = 0.0;

    double volume() const;

    /// A ball around `points` within a few percent of the smallest one: Ritter's two-pass ball,
    /// then passes that pull the centre towards the farthest point with a shrinking step (keeping
    /// the best ball found). The radius is the exact farthest distance from the final centre,
    /// grown by a relative margin (1e-9 of the coordinates' magnitude) so rounding leaves no
    /// point outside. Deterministic. `points` must not be empty.
    static Sphere fit(const std::vector<Vec3> &points);

    /// True when `p` lies in the ball (inclusive).
    bool contains(const Vec3 &p) const { return (p - center).squaredNorm() <= radius * radius; }

    /// The same ball mapped by `pose`.
    Sphere transformed(const RigidTransform &pose) const { return {pose.apply(center), radius}; }
};

/// True unless the balls are more than `tolerance` apart.
bool spheresOverlap(const Sphere &a, const Sphere &b, double tolerance);

/// The distance between the balls less `tolerance`, never below zero (a lower bound on the
/// distance between anything they contain).
double sphereDistanceLowerBound(const Sphere &a, const Sphere &b, double tolerance);
}  // namespace hcd
