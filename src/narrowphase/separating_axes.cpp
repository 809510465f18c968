// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/separating_axes.h"

#include "axis_search.h"
#include "working_frame.h"

#include <limits>

namespace hcd
{
double separatingAxisGap(const ConvexPiece &a, const ConvexPiece &b, Vec3 *axis)
{
    return AxisSearch(a, b, std::numeric_limits<double>::infinity()).run(axis);
}

bool convexPiecesIntersectSat(const ConvexPiece &a, const ConvexPiece &b)
{
    const double tolerance = pairTolerance(a, b);
    return AxisSearch(a, b, tolerance).run(nullptr) <= tolerance;
}
}  // namespace hcd
