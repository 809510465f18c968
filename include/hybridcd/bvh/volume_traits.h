// SPDX-License-Identifier: BSD-3-Clause
// What a hierarchy needs from a bounding volume: fitting, a split direction, placement and tests.
//
// Each specialisation adapts one volume type. Every test must be conservative: `overlap` may say
// true for disjoint volumes but never false for volumes that share a point (within `tolerance`
// of slack for rounding), and `lowerBound` must never exceed the true distance.
#pragma once

#include "hybridcd/bv/obb.h"

#include <cmath>
#include <vector>

namespace hcd
{
template <class Volume>
struct VolumeTraits;

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
};
}  // namespace hcd
