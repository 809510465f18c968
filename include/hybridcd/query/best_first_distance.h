// SPDX-License-Identifier: BSD-3-Clause
// Best-first branch and bound for the distance between two hierarchies: the one search behind
// every tree checker's clearance (volume trees, the octree), whatever their volumes and fan-out.
#pragma once

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_mesh.h"
#include "hybridcd/query/traversal_stack.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace hcd
{
/// The most children one split of a node pair yields (an octree cell has eight).
inline constexpr int kMaxPairChildren = 8;

/// The smallest distance between the contents of the root pair {0, 0}, or +infinity if every leaf
/// pair lies beyond it. Expands only pairs whose bound is below the best distance found yet, and
/// stops at the first pair whose bound reaches it, so it is exact whenever the bounds are lower
/// bounds:
/// - `rootBound`: a lower bound on the distance between the root pair's contents;
/// - `boundedSplit(pair, best, out)`: for a pair that is not a pair of leaves, writes its child
///   pairs with lower bounds on their contents' distances (at most kMaxPairChildren; a bound may be
///   any value >= best once the child is known to lie beyond best) and returns their number;
/// - `leafDistance(pair, best)`: for a pair of leaves, the smaller of best and their contents' exact
///   distance;
/// - `isLeafPair(pair)`.
/// The nearest child goes on directly, without a trip through the queue, when nothing queued is
/// nearer. A child that is a pair of leaves, with its bound below the best, is measured at once
/// instead of queued: measuring costs little more than the trip through the queue, most such pairs
/// would be measured later anyway, and an early measure lowers the best for the pairs after it
/// (clearance on alpha-1.5 and bugtrap 6% fewer instructions, 9% less time; bench/README.md,
/// section 1). `queue` is scratch from the caller's query context.
template <class IsLeafPair, class LeafDistance, class BoundedSplit>
double bestFirstDistanceBounded(NearestPairQueue &queue, double rootBound, IsLeafPair &&isLeafPair,
                                LeafDistance &&leafDistance, BoundedSplit &&boundedSplit)
{
    double best = std::numeric_limits<double>::infinity();
    queue.clear();
    BoundedPair current{{0, 0}, rootBound};
    bool haveCurrent = true;
    BoundedPair children[kMaxPairChildren];
    while (haveCurrent || !queue.empty())
    {
        if (!haveCurrent)
            current = queue.pop();
        haveCurrent = false;
        if (current.bound >= best)
            break;  // the nearest pair left is no nearer than the best: none is
        if (isLeafPair(current.pair))
        {
            best = leafDistance(current.pair, best);
            continue;
        }
        const int count = boundedSplit(current.pair, best, children);
        // The nearest child is kept aside, the rest queued unless already beyond.
        BoundedPair nearest{{0, 0}, std::numeric_limits<double>::infinity()};
        bool haveNearest = false;
        for (int k = 0; k < count; ++k)
        {
            const BoundedPair &child = children[k];
            if (child.bound >= best)
                continue;
            if (isLeafPair(child.pair))
            {
                best = leafDistance(child.pair, best);  // at once: see above
                continue;
            }
            if (!haveNearest || child.bound < nearest.bound)
            {
                if (haveNearest)
                    queue.push(nearest);
                nearest = child;
                haveNearest = true;
            }
            else
                queue.push(child);
        }
        if (!haveNearest)
            continue;
        if (queue.empty() || nearest.bound <= queue.nearestBound())
        {
            current = nearest;
            haveCurrent = true;
        }
        else
            queue.push(nearest);
    }
    return best;
}

/// bestFirstDistanceBounded with each child's bound from `bound(pair, best)` (a lower bound; any
/// value >= best once it knows the pair is beyond best, a cheap early out) and the children from
/// `split(pair, children)` (writes at most kMaxPairChildren, returns their number).
template <class Bound, class IsLeafPair, class LeafDistance, class Split>
double bestFirstDistance(NearestPairQueue &queue, Bound &&bound, IsLeafPair &&isLeafPair, LeafDistance &&leafDistance,
                         Split &&split)
{
    const double rootBound = bound(NodePair{0, 0}, std::numeric_limits<double>::infinity());
    return bestFirstDistanceBounded(queue, rootBound, isLeafPair, leafDistance,
                                    [&](const NodePair &pair, double best, BoundedPair *out) {
                                        NodePair children[kMaxPairChildren];
                                        const int count = split(pair, children);
                                        for (int k = 0; k < count; ++k)
                                            out[k] = {children[k], bound(children[k], best)};
                                        return count;
                                    });
}

/// A leaf pair's part of leafDistance: the smaller of `best` and the distances between the placed
/// robot triangles robotTriangles[0, robotCount) (a PlacedRobot's triangles) and the environment
/// triangles environmentTriangles[0, environmentCount) of `environment`, counting each pair in
/// `tests`. Only for a pose already found free: the pairs are known disjoint.
template <class Placed>
double leafTrianglesDistance(Placed &placed, const std::uint32_t *robotTriangles, std::uint32_t robotCount,
                             const TriangleMesh &environment, const std::uint32_t *environmentTriangles,
                             std::uint32_t environmentCount, double best, std::uint64_t &tests)
{
    for (std::uint32_t i = 0; i < robotCount; ++i)
    {
        const auto &a = placed.triangle(robotTriangles[i]);
        for (std::uint32_t j = 0; j < environmentCount; ++j)
        {
            const std::uint32_t et = environmentTriangles[j];
            ++tests;
            best = disjointTriangleDistanceBelow(a.corners[0], a.corners[1], a.corners[2], environment.corner(et, 0),
                                                 environment.corner(et, 1), environment.corner(et, 2), best);
        }
    }
    return best;
}
}  // namespace hcd
