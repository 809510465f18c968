// SPDX-License-Identifier: BSD-3-Clause
// Which side of a triangle's plane another triangle lies on, certified by orient3d()'s filter
// (PlaneOrientationFilter): the plane test that both the intersection test
// (triangle_intersection.cpp) and the proximity test (triangle_distance.cpp) try before anything
// exact. Internal to geometry/.
#pragma once

#include "hybridcd/geometry/exact_predicates.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hcd
{
// The side of the plane of (q0, q1, q2) each of p0, p1, p2 lies on, as orient3d(q0, q1, q2, p_i)
// would give it, where the filter certifies it; 0 where it does not (the exact predicate decides
// those). Returns true when all three lie strictly on one side.
inline bool filteredSides(const PlaneOrientationFilter &plane, const Vec3 &p0, const Vec3 &p1, const Vec3 &p2,
                          int sides[3])
{
    sides[0] = plane.side(p0);
    sides[1] = plane.side(p1);
    sides[2] = plane.side(p2);
    return sides[0] != 0 && sides[0] == sides[1] && sides[1] == sides[2];
}

// A lower bound on the distance from the triangle (p0, p1, p2) to the plane of (q0, q1, q2) when
// the first lies certainly on one side of it, else 0: the least certified determinant (its value
// less its error bound) over the largest length the exact normal can have, lowered once more for
// the rounding of the norm and the division.
inline double planeGap(const Vec3 &q0, const Vec3 &q1, const Vec3 &q2, const Vec3 &p0, const Vec3 &p1, const Vec3 &p2)
{
    const PlaneOrientationFilter plane(q0, q1, q2);
    double least = std::numeric_limits<double>::infinity();
    int side = 0;
    for (const Vec3 *p : {&p0, &p1, &p2})
    {
        double offset = 0.0, bound = 0.0;
        const int s = plane.side(*p, &offset, &bound);
        if (s == 0 || (side != 0 && s != side))
            return 0.0;
        side = s;
        least = std::min(least, std::fabs(offset) - bound);
    }
    const double normalLength =
        plane.normal().norm() + PlaneOrientationFilter::kRelativeError * plane.normalMagnitude().norm();
    const double gap = least / normalLength;
    return std::isfinite(gap) ? gap * (1.0 - 8.0 * std::numeric_limits<double>::epsilon()) : 0.0;
}
}  // namespace hcd
