// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/candidate_axes.h"

#include <cmath>

namespace hcd
{
std::vector<Vec3> distinctEdgeDirections(const ConvexPiece &p)
{
    std::vector<Vec3> directions;
    directions.reserve(p.edges.size());
    for (const auto &e : p.edges)
    {
        const Vec3 d = p.vertices[std::size_t(e[1])] - p.vertices[std::size_t(e[0])];
        const double length = d.norm();
        if (!(length > 0.0) || !std::isfinite(length))
            continue;
        const Vec3 u = d / length;
        // 1e-12 rad: far below anything that could change which candidate wins.
        if (std::none_of(directions.begin(), directions.end(),
                         [&](const Vec3 &w) { return u.cross(w).squaredNorm() <= 1e-24; }))
            directions.push_back(u);
    }
    return directions;
}
}  // namespace hcd
