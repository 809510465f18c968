// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/obb_tree_checker.h"

#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/query/traversal_stack.h"

namespace hcd
{
ObbTreeChecker::ObbTreeChecker(CollisionScene scene, unsigned maxLeafTriangles)
    : scene_(std::move(scene)),
      robotTree_(scene_.robot, maxLeafTriangles),
      environmentTree_(scene_.environment, maxLeafTriangles),
      robotRadius_(scene_.robot->radiusAboutOrigin()),
      environmentMagnitude_(scene_.environment->radiusAboutOrigin())
{
}

bool ObbTreeChecker::collides(const RigidTransform &worldFromRobot, QueryStats *stats) const
{
    if (!worldFromRobot.isFinite())
        return true;
    if (robotTree_.empty() || environmentTree_.empty())
        return false;

    // Rounding in the box test scales with the coordinates involved; 1e-10 of them covers it many
    // times over while costing nothing measurable in culling.
    const double tolerance =
        1e-10 * (1.0 + worldFromRobot.translation.norm() + robotRadius_ + environmentMagnitude_);
    const auto &rNodes = robotTree_.nodes();
    const auto &eNodes = environmentTree_.nodes();
    const TriangleMesh &robot = *scene_.robot, &env = *scene_.environment;

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
        if (!obbsOverlap(rn.box, worldFromRobot, en.box, tolerance))
            continue;
        if (rn.isLeaf() && en.isLeaf())
        {
            for (std::uint32_t i = 0; i < rn.triangleCount && !hit; ++i)
            {
                const std::uint32_t rt = robotTree_.triangleOrder()[rn.firstTriangle + i];
                const Vec3 a0 = worldFromRobot.apply(robot.corner(rt, 0));
                const Vec3 a1 = worldFromRobot.apply(robot.corner(rt, 1));
                const Vec3 a2 = worldFromRobot.apply(robot.corner(rt, 2));
                for (std::uint32_t j = 0; j < en.triangleCount; ++j)
                {
                    const std::uint32_t et = environmentTree_.triangleOrder()[en.firstTriangle + j];
                    ++triangleTests;
                    if (trianglesIntersect(a0, a1, a2, env.corner(et, 0), env.corner(et, 1), env.corner(et, 2)))
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

std::vector<HierarchyReport> ObbTreeChecker::hierarchies() const
{
    return {{"robot OBB tree", robotTree_.nodes().size(), robotTree_.depth(), robotTree_.buildSeconds(),
             robotTree_.memoryBytes()},
            {"environment OBB tree", environmentTree_.nodes().size(), environmentTree_.depth(),
             environmentTree_.buildSeconds(), environmentTree_.memoryBytes()}};
}
}  // namespace hcd
