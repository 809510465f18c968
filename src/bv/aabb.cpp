// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bv/aabb.h"
#include "hybridcd/bv/fixed_aabb.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hcd
{
namespace
{
// Distance between two axis-aligned boxes given by centre offset and summed half extents.
double boxGap(const Vec3 &offset, const Vec3 &sumHalf, double tolerance)
{
    const Vec3 gap = (offset.cwiseAbs() - sumHalf).cwiseMax(0.0);
    return std::max(0.0, gap.norm() - tolerance);
}
}  // namespace

Aabb Aabb::fit(const std::vector<Vec3> &points)
{
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    for (const Vec3 &p : points)
    {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double magnitude = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    return {0.5 * (lo + hi), (0.5 * (hi - lo)).array() + (1e-9 * magnitude + 1e-300)};
}

Aabb Aabb::transformed(const RigidTransform &pose) const
{
    const Vec3 c = pose.apply(center);
    const Vec3 h = pose.rotation.cwiseAbs() * halfExtents;
    // The products and sums above round; the relative pad covers them and the mapped centre's.
    const double pad = 1e-12 * (h.maxCoeff() + c.cwiseAbs().maxCoeff()) + 1e-300;
    return {c, h.array() + pad};
}

bool aabbsOverlap(const Aabb &a, const Aabb &b, double tolerance)
{
    return ((a.center - b.center).cwiseAbs().array() <= (a.halfExtents + b.halfExtents).array() + tolerance).all();
}

double aabbDistanceLowerBound(const Aabb &a, const Aabb &b, double tolerance)
{
    return boxGap(a.center - b.center, a.halfExtents + b.halfExtents, tolerance);
}

bool fixedAabbsOverlap(const FixedAabb &a, const FixedAabb &b, double tolerance)
{
    return ((a.center - b.center).cwiseAbs().array() <= a.halfSide + b.halfSide + tolerance).all();
}

double fixedAabbDistanceLowerBound(const FixedAabb &a, const FixedAabb &b, double tolerance)
{
    return boxGap(a.center - b.center, Vec3::Constant(a.halfSide + b.halfSide), tolerance);
}
}  // namespace hcd
