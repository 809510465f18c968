// SPDX-License-Identifier: BSD-3-Clause
// Which side of a triangle's plane another triangle lies on, decided in floating point with a
// rounding bound: the plane test that both the intersection test (triangle_intersection.cpp) and
// the proximity test (triangle_distance.cpp) try before anything exact. Internal to geometry/.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hcd
{
// The corners p0, p1, p2 against the plane of the triangle (q0, q1, q2), all in one frame.
struct PlaneSide
{
    /// +1 or -1 when every corner lies strictly on that side of the exact plane (certified), else 0.
    int side = 0;
    /// When side != 0: the smallest |orient3d(q0, q1, q2, p_i)| is at least this (> 0).
    double leastDeterminant = 0.0;
    /// The computed normal (q1 - q0) x (q2 - q0), and a bound on its error in length.
    double normalLength = 0.0, normalError = 0.0;
};

// The normal once, then one dot product per corner, each trusted only when it exceeds its rounding
// bound: 8 eps times the sum of the absolute products that make it up covers the differences, the
// cross product and the dot product (Shewchuk's static filter for orient3d). Over- or underflow
// leaves the bound unmet, never a wrong sign. `withLength` also measures the normal (a square root).
inline PlaneSide planeSide(const Vec3 &q0, const Vec3 &q1, const Vec3 &q2, const Vec3 &p0, const Vec3 &p1,
                           const Vec3 &p2, bool withLength)
{
    const Vec3 e1 = q1 - q0, e2 = q2 - q0;
    const Vec3 n = e1.cross(e2);
    const Vec3 magnitude(std::fabs(e1.y() * e2.z()) + std::fabs(e1.z() * e2.y()),
                         std::fabs(e1.z() * e2.x()) + std::fabs(e1.x() * e2.z()),
                         std::fabs(e1.x() * e2.y()) + std::fabs(e1.y() * e2.x()));
    constexpr double kRounding = 8.0 * std::numeric_limits<double>::epsilon();
    PlaneSide out;
    double least = std::numeric_limits<double>::infinity();
    int side = 0;
    for (const Vec3 *p : {&p0, &p1, &p2})
    {
        const Vec3 d = *p - q0;
        const double offset = n.dot(d);
        const double bound = kRounding * magnitude.dot(d.cwiseAbs());
        const int sign = offset > bound ? 1 : offset < -bound ? -1 : 0;
        if (sign == 0 || (side != 0 && sign != side))
            return out;
        side = sign;
        least = std::min(least, std::fabs(offset) - bound);
    }
    out.side = side;
    out.leastDeterminant = least;
    if (withLength)
    {
        // Each component of the exact normal is within 4 eps of its magnitude of the computed one.
        out.normalLength = n.norm();
        out.normalError = kRounding * magnitude.norm();
    }
    return out;
}

// Whether p0, p1, p2 lie strictly on one side of the plane of (q0, q1, q2). False means "not
// separated" or "not sure": exact predicates decide then.
inline bool separatedByPlane(const Vec3 &q0, const Vec3 &q1, const Vec3 &q2, const Vec3 &p0, const Vec3 &p1,
                             const Vec3 &p2)
{
    return planeSide(q0, q1, q2, p0, p1, p2, false).side != 0;
}

// A lower bound on the distance from the triangle (p0, p1, p2) to the plane of (q0, q1, q2) when
// the first lies certainly on one side of it, else 0: the least determinant over the largest the
// exact normal's length can be, lowered by the rounding of the norm and the division.
inline double planeGap(const Vec3 &q0, const Vec3 &q1, const Vec3 &q2, const Vec3 &p0, const Vec3 &p1, const Vec3 &p2)
{
    const PlaneSide s = planeSide(q0, q1, q2, p0, p1, p2, true);
    if (s.side == 0)
        return 0.0;
    const double gap = s.leastDeterminant / (s.normalLength + s.normalError);
    return std::isfinite(gap) ? gap * (1.0 - 8.0 * std::numeric_limits<double>::epsilon()) : 0.0;
}
}  // namespace hcd
