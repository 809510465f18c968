// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/obb_tree_checker.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/query/placed_robot.h"
#include "hybridcd/query/traversal_stack.h"

#include <cmath>

namespace hcd
{
ObbTreeChecker::ObbTreeChecker(CollisionScene scene, unsigned maxLeafTriangles)
    : scene_(std::move(scene)),
      robotTree_(scene_.robot, maxLeafTriangles),
      environmentTree_(scene_.environment, maxLeafTriangles),
      robotRadius_(scene_.robot->radiusAboutOrigin()),
      environmentMagnitude_(scene_.environment->radiusAboutOrigin())
{
    const TriangleMesh &env = *scene_.environment;
    environmentTriangleBounds_.reserve(env.triangleCount());
    for (std::size_t t = 0; t < env.triangleCount(); ++t)
    {
        const Vec3 &a = env.corner(t, 0), &b = env.corner(t, 1), &c = env.corner(t, 2);
        environmentTriangleBounds_.push_back({a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)});
    }
}

double ObbTreeChecker::toleranceFor(const RigidTransform &worldFromRobot) const
{
    // Rounding in the box tests scales with the coordinates involved; 1e-10 of them covers it
    // many times over while costing nothing measurable in culling.
    return 1e-10 * (1.0 + worldFromRobot.translation.norm() + robotRadius_ + environmentMagnitude_);
}

bool ObbTreeChecker::collides(const RigidTransform &worldFromRobot, QueryStats *stats) const
{
    return anyPairWithin(worldFromRobot, 0.0, stats);
}

bool ObbTreeChecker::withinDistance(const RigidTransform &worldFromRobot, double delta, QueryStats *stats) const
{
    return anyPairWithin(worldFromRobot, std::max(0.0, delta), stats);
}

bool ObbTreeChecker::anyPairWithin(const RigidTransform &worldFromRobot, double delta, QueryStats *stats) const
{
    if (!worldFromRobot.isFinite())
        return true;
    if (robotTree_.empty() || environmentTree_.empty())
        return false;

    const double tolerance = toleranceFor(worldFromRobot);
    // Exact comparisons on coordinates need no tolerance; the proximity slack covers delta.
    const double boundsSlack = delta > 0.0 ? delta * (1.0 + 1e-9) + tolerance : 0.0;
    const auto &rNodes = robotTree_.nodes();
    const auto &eNodes = environmentTree_.nodes();
    const TriangleMesh &env = *scene_.environment;
    PlacedRobot placed(robotTree_, worldFromRobot);

    std::uint64_t boxTests = 0, triangleTests = 0;
    bool hit = false;
    TraversalStack stack;
    stack.push({0, 0});
    while (!stack.empty() && !hit)
    {
        const NodePair pair = stack.pop();
        const ObbTree::Node &rn = rNodes[pair.robot];
        const ObbTree::Node &en = eNodes[pair.environment];
        ++boxTests;
        // Circumscribed spheres first (a few flops), then the separating-axis test. Growing the
        // tolerance by delta keeps every pair closer than delta (the axes have length <= 1).
        const Obb &robotBox = placed.box(pair.robot);
        const double reach = rn.radius + en.radius + tolerance + delta;
        if ((robotBox.center - en.box.center).squaredNorm() > reach * reach ||
            !obbsOverlap(robotBox, en.box, tolerance + delta))
            continue;
        if (rn.isLeaf() && en.isLeaf())
        {
            for (std::uint32_t i = 0; i < rn.triangleCount && !hit; ++i)
            {
                const PlacedTriangle &a = placed.triangle(robotTree_.triangleOrder()[rn.firstTriangle + i]);
                for (std::uint32_t j = 0; j < en.triangleCount; ++j)
                {
                    const std::uint32_t et = environmentTree_.triangleOrder()[en.firstTriangle + j];
                    const TriangleBounds &eb = environmentTriangleBounds_[et];
                    if ((a.min.array() > eb.max.array() + boundsSlack).any() ||
                        (eb.min.array() > a.max.array() + boundsSlack).any())
                        continue;
                    ++triangleTests;
                    const Vec3 &b0 = env.corner(et, 0), &b1 = env.corner(et, 1), &b2 = env.corner(et, 2);
                    if (delta == 0.0 ? trianglesIntersect(a.corners[0], a.corners[1], a.corners[2], b0, b1, b2)
                                     : triangleDistance(a.corners[0], a.corners[1], a.corners[2], b0, b1, b2) <=
                                           delta * (1.0 + 1e-9) + tolerance)
                    {
                        hit = true;
                        break;
                    }
                }
            }
            continue;
        }
        // Split the node whose box is larger (by its largest extent); leaves cannot be split.
        const bool splitRobot =
            en.isLeaf() || (!rn.isLeaf() && rn.box.halfExtents.maxCoeff() >= en.box.halfExtents.maxCoeff());
        if (splitRobot)
        {
            stack.push({std::uint32_t(rn.firstChild + 1), pair.environment});
            stack.push({std::uint32_t(rn.firstChild), pair.environment});
        }
        else
        {
            stack.push({pair.robot, std::uint32_t(en.firstChild + 1)});
            stack.push({pair.robot, std::uint32_t(en.firstChild)});
        }
    }
    if (stats)
    {
        stats->boundingVolumeTests += boxTests;
        stats->primitiveTests += triangleTests;
    }
    return hit;
}

double ObbTreeChecker::distance(const RigidTransform &worldFromRobot, QueryStats *stats) const
{
    if (!worldFromRobot.isFinite())
        return 0.0;
    if (robotTree_.empty() || environmentTree_.empty())
        return std::numeric_limits<double>::infinity();
    if (collides(worldFromRobot, stats))
        return 0.0;

    // Branch and bound: descend pairs whose box lower bound is below the best distance found yet,
    // nearer pair first, so the bound tightens early.
    const double tolerance = toleranceFor(worldFromRobot);
    const auto &rNodes = robotTree_.nodes();
    const auto &eNodes = environmentTree_.nodes();
    const TriangleMesh &env = *scene_.environment;
    PlacedRobot placed(robotTree_, worldFromRobot);
    double best = std::numeric_limits<double>::infinity();
    std::uint64_t boxTests = 0, triangleTests = 0;
    const auto lowerBound = [&](const NodePair &p) {
        ++boxTests;
        return obbDistanceLowerBound(placed.box(p.robot), eNodes[p.environment].box, tolerance);
    };
    TraversalStack stack;
    stack.push({0, 0});
    while (!stack.empty())
    {
        const NodePair pair = stack.pop();
        const ObbTree::Node &rn = rNodes[pair.robot];
        const ObbTree::Node &en = eNodes[pair.environment];
        if (lowerBound(pair) >= best)
            continue;
        if (rn.isLeaf() && en.isLeaf())
        {
            for (std::uint32_t i = 0; i < rn.triangleCount; ++i)
            {
                const PlacedTriangle &a = placed.triangle(robotTree_.triangleOrder()[rn.firstTriangle + i]);
                for (std::uint32_t j = 0; j < en.triangleCount; ++j)
                {
                    const std::uint32_t et = environmentTree_.triangleOrder()[en.firstTriangle + j];
                    ++triangleTests;
                    best = std::min(best, triangleDistance(a.corners[0], a.corners[1], a.corners[2], env.corner(et, 0),
                                                           env.corner(et, 1), env.corner(et, 2)));
                }
            }
            continue;
        }
        const bool splitRobot =
            en.isLeaf() || (!rn.isLeaf() && rn.box.halfExtents.maxCoeff() >= en.box.halfExtents.maxCoeff());
        NodePair first = splitRobot ? NodePair{std::uint32_t(rn.firstChild), pair.environment}
                                    : NodePair{pair.robot, std::uint32_t(en.firstChild)};
        NodePair second = splitRobot ? NodePair{std::uint32_t(rn.firstChild + 1), pair.environment}
                                     : NodePair{pair.robot, std::uint32_t(en.firstChild + 1)};
        if (lowerBound(first) > lowerBound(second))
            std::swap(first, second);
        stack.push(second);  // popped after the nearer one
        stack.push(first);
    }
    if (stats)
    {
        stats->boundingVolumeTests += boxTests;
        stats->primitiveTests += triangleTests;
    }
    return best;
}

std::vector<HierarchyReport> ObbTreeChecker::hierarchies() const
{
    return {{"robot OBB tree", robotTree_.nodes().size(), robotTree_.depth(), robotTree_.buildSeconds(),
             robotTree_.memoryBytes()},
            {"environment OBB tree", environmentTree_.nodes().size(), environmentTree_.depth(),
             environmentTree_.buildSeconds(), environmentTree_.memoryBytes() +
                                                  environmentTriangleBounds_.capacity() * sizeof(TriangleBounds)}};
}
}  // namespace hcd
