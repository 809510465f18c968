// SPDX-License-Identifier: BSD-3-Clause
// How tightly a hierarchy's volumes wrap their content (`inspect`, the bench table).
#pragma once

#include "hybridcd/bvh/volume_tree.h"
#include "hybridcd/narrowphase/convex_decomposition.h"

#include <limits>
#include <utility>
#include <vector>

namespace hcd
{
/// Mean node volume over content hull volume, on up to 400 evenly spread nodes whose content is not
/// flat, and the number of nodes it was taken over (NaN and 0 when none qualifies).
template <class Volume>
std::pair<double, std::size_t> meanVolumeRatio(const VolumeTree<Volume> &tree)
{
    const auto &nodes = tree.nodes();
    const std::size_t step = std::max<std::size_t>(1, nodes.size() / 400);
    double sum = 0.0;
    std::size_t count = 0;
    std::vector<Vec3> points;
    for (std::size_t i = 0; i < nodes.size(); i += step)
    {
        points.clear();
        for (std::uint32_t k = 0; k < nodes[i].triangleCount; ++k)
            for (int c = 0; c < 3; ++c)
                points.push_back(tree.mesh().corner(tree.triangleOrder()[nodes[i].firstTriangle + k], c));
        const ConvexPiece hull = ConvexPiece::hullOf(points);
        const double content = hullVolume(hull);
        const double extent = hull.magnitude();
        if (!(content > 1e-9 * extent * extent * extent))
            continue;  // flat content (a single triangle, a planar patch): the ratio is unbounded
        sum += VolumeTraits<Volume>::volume(nodes[i].volume) / content;
        ++count;
    }
    return {count ? sum / double(count) : std::numeric_limits<double>::quiet_NaN(), count};
}
}  // namespace hcd
