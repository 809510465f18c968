// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/octree_checker.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/narrowphase/convex_decomposition.h"
#include "hybridcd/query/best_first_distance.h"
#include "hybridcd/query/placed_robot.h"
#include "hybridcd/query/traversal_stack.h"
#include "hybridcd/query/volume_ratio.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <unordered_set>

namespace hcd
{
namespace
{
Obb cellBox(const Octree::Cell &c) { return {c.center, Mat3::Identity(), Vec3::Constant(c.halfSide)}; }

double cellRadius(const Octree::Cell &c) { return std::sqrt(3.0) * c.halfSide * (1.0 + 1e-12); }
}  // namespace

OctreeChecker::OctreeChecker(CollisionScene scene, std::string name, Octree::Limits limits)
    : robotFaces_(withoutRepeatedFaces(scene.robot)),
      environmentFaces_(withoutRepeatedFaces(scene.environment)),
      scene_{robotFaces_.mesh,  environmentFaces_.mesh, std::move(scene.robotName), std::move(scene.environmentName),
             scene.planarPoses, scene.turnsAboutRobotZ},
      name_(std::move(name)),
      robotTree_(scene_.robot, 1),
      octree_(scene_.environment, limits),
      robotRadius_(scene_.robot->radiusAboutOrigin()),
      environmentMagnitude_(scene_.environment->radiusAboutOrigin())
{
    // Reaches from the robot origin, or from its z axis when motions turn about it.
    for (const auto &node : robotTree_.nodes())
        robotNodeReach_.push_back((turnReach(node.volume.center, scene_.turnsAboutRobotZ) + node.radius) *
                                  (1.0 + 1e-12));
    robotTriangleReach_ = triangleTurnReaches(*scene_.robot, scene_.turnsAboutRobotZ);
    const TriangleMesh &env = *scene_.environment;
    environmentTriangleBounds_.reserve(env.triangleCount());
    for (std::size_t t = 0; t < env.triangleCount(); ++t)
    {
        const Vec3 &a = env.corner(t, 0), &b = env.corner(t, 1), &c = env.corner(t, 2);
        environmentTriangleBounds_.push_back({a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)});
    }
}

double OctreeChecker::toleranceFor(const RigidTransform &worldFromRobot) const
{
    // As the volume trees: 1e-10 of the coordinates involved covers rounding in the box tests.
    return 1e-10 * (worldFromRobot.translation.norm() + robotRadius_ + environmentMagnitude_);
}

bool OctreeChecker::doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    return anyPairWithin(worldFromRobot, {}, context);
}

bool OctreeChecker::doWithinDistance(const RigidTransform &worldFromRobot, double delta, QueryContext &context) const
{
    return anyPairWithin(worldFromRobot, {std::max(0.0, delta), 0.0}, context);
}

bool OctreeChecker::doWithinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack,
                                          double radialSlack, double robotRadius, QueryContext &context) const
{
    (void)robotRadius;  // per-node reaches are tighter than the robot's radius
    return anyPairWithin(worldFromRobot, {std::max(0.0, translationSlack), std::max(0.0, radialSlack)}, context);
}

bool OctreeChecker::anyPairWithin(const RigidTransform &worldFromRobot, Slack slack, QueryContext &context,
                                  std::vector<ContactPair> *found, std::size_t limit) const
{
    if (!worldFromRobot.isFinite())
        return true;
    if (robotTree_.empty() || octree_.empty())
        return false;

    const double tolerance = toleranceFor(worldFromRobot);
    const bool proximity = slack.translation > 0.0 || slack.radial > 0.0;
    const auto &rNodes = robotTree_.nodes();
    const auto &cells = octree_.cells();
    const auto &references = octree_.triangleReferences();
    const TriangleMesh &env = *scene_.environment;
    PlacedRobot<Obb> placed(robotTree_, worldFromRobot, context);
    // Contacts are listed once although a triangle pair may meet in several cells.
    std::unordered_set<std::uint64_t> listed;

    std::uint64_t boxTests = 0, triangleTests = 0;
    const auto trianglesWithin = [&](std::uint32_t rt, std::uint32_t et) {
        const PlacedTriangle &a = placed.triangle(rt);
        const double triangleDelta = slack.at(robotTriangleReach_[rt]);
        const double boundsSlack = proximity ? triangleDelta * (1.0 + 1e-9) + tolerance : 0.0;
        const TriangleBounds &eb = environmentTriangleBounds_[et];
        if ((a.min.array() > eb.max.array() + boundsSlack).any() ||
            (eb.min.array() > a.max.array() + boundsSlack).any())
            return false;
        ++triangleTests;
        const Vec3 &b0 = env.corner(et, 0), &b1 = env.corner(et, 1), &b2 = env.corner(et, 2);
        return !proximity ? trianglesIntersect(a.corners[0], a.corners[1], a.corners[2], b0, b1, b2)
                          : trianglesWithinDistance(a.corners[0], a.corners[1], a.corners[2], b0, b1, b2,
                                                    triangleDelta * (1.0 + 1e-9) + tolerance);
    };

    bool hit = false;
    TraversalStack stack;  // pairs (robot node, cell)
    stack.push({0, 0});
    while (!stack.empty() && !hit)
    {
        const NodePair pair = stack.pop();
        const VolumeTree<Obb>::Node &rn = rNodes[pair.robot];
        const Octree::Cell &cell = cells[pair.environment];
        ++boxTests;
        const Obb &robotBox = placed.volume(pair.robot);
        const double delta = slack.at(robotNodeReach_[pair.robot]);
        const double reach = rn.radius + cellRadius(cell) + tolerance + delta;
        // Spheres first, then the separating axes (of length at most 1, so growing the tolerance
        // by delta keeps every pair closer than delta).
        if ((robotBox.center - cell.center).squaredNorm() > reach * reach ||
            !obbsOverlap(robotBox, cellBox(cell), tolerance + delta))
            continue;
        if (rn.isLeaf() && cell.isLeaf())
        {
            for (std::uint32_t i = 0; i < rn.triangleCount && !hit; ++i)
            {
                const std::uint32_t rt = robotTree_.triangleOrder()[rn.firstTriangle + i];
                for (std::uint32_t j = 0; j < cell.triangleCount; ++j)
                {
                    const std::uint32_t et = references[cell.firstTriangle + j];
                    if (found && listed.count((std::uint64_t(rt) << 32) | et))
                        continue;
                    if (!trianglesWithin(rt, et))
                        continue;
                    if (!found)
                    {
                        hit = true;
                        break;
                    }
                    listed.insert((std::uint64_t(rt) << 32) | et);
                    const PlacedTriangle &a = placed.triangle(rt);
                    found->push_back({ContactPair::Kind::Triangles, rt, et,
                                      triangleContactPoint(a.corners[0], a.corners[1], a.corners[2], env.corner(et, 0),
                                                           env.corner(et, 1), env.corner(et, 2))});
                    if ((hit = found->size() >= limit))
                        break;
                }
            }
            continue;
        }
        // Split the larger of the two (by circumscribed sphere); leaves cannot be split.
        const bool splitRobot = cell.isLeaf() || (!rn.isLeaf() && rn.radius >= cellRadius(cell));
        if (splitRobot)
        {
            stack.push({std::uint32_t(rn.firstChild + 1), pair.environment});
            stack.push({std::uint32_t(rn.firstChild), pair.environment});
        }
        else
            for (std::uint32_t k = cell.childCount; k-- > 0;)
                stack.push({pair.robot, std::uint32_t(cell.firstChild) + k});
    }
    context.stats.boundingVolumeTests += boxTests;
    context.stats.primitiveTests += triangleTests;
    return hit;
}

std::vector<ContactPair> OctreeChecker::doContacts(const RigidTransform &worldFromRobot, std::size_t limit,
                                                   QueryContext &context) const
{
    std::vector<ContactPair> found;
    if (limit > 0 && worldFromRobot.isFinite())
        anyPairWithin(worldFromRobot, {}, context, &found, limit);
    for (ContactPair &c : found)
    {
        c.robotElement = robotFaces_.source(c.robotElement);
        c.environmentElement = environmentFaces_.source(c.environmentElement);
    }
    return found;
}

double OctreeChecker::doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    if (!worldFromRobot.isFinite())
        return 0.0;
    if (robotTree_.empty() || octree_.empty())
        return std::numeric_limits<double>::infinity();
    if (doCollides(worldFromRobot, context))
        return 0.0;

    // Branch and bound, nearest pair first (best_first_distance.h), as the volume trees do.
    const double tolerance = toleranceFor(worldFromRobot);
    const auto &rNodes = robotTree_.nodes();
    const auto &cells = octree_.cells();
    const auto &references = octree_.triangleReferences();
    const TriangleMesh &env = *scene_.environment;
    PlacedRobot<Obb> placed(robotTree_, worldFromRobot, context);
    std::uint64_t boxTests = 0, triangleTests = 0;
    const auto lowerBound = [&](const NodePair &p, double best) {
        ++boxTests;
        const Obb &robotBox = placed.volume(p.robot);
        const Octree::Cell &cell = cells[p.environment];
        const double sphereGap =
            (robotBox.center - cell.center).norm() - rNodes[p.robot].radius - cellRadius(cell) - tolerance;
        if (sphereGap >= best)  // beyond the best distance already: no box bound needed
            return sphereGap;
        return std::max(sphereGap, obbDistanceLowerBound(robotBox, cellBox(cell), tolerance));
    };
    const auto isLeafPair = [&](const NodePair &p) {
        return rNodes[p.robot].isLeaf() && cells[p.environment].isLeaf();
    };
    // doCollides answered free above: no pair of triangles meets.
    const auto leafDistance = [&](const NodePair &p, double best) {
        const VolumeTree<Obb>::Node &rn = rNodes[p.robot];
        const Octree::Cell &cell = cells[p.environment];
        return leafTrianglesDistance(placed, robotTree_.triangleOrder().data() + rn.firstTriangle, rn.triangleCount,
                                     env, references.data() + cell.firstTriangle, cell.triangleCount, best,
                                     triangleTests);
    };
    // The robot node is split while it is larger than the cell (or the cell is a leaf).
    const auto split = [&](const NodePair &p, NodePair *children) {
        const VolumeTree<Obb>::Node &rn = rNodes[p.robot];
        const Octree::Cell &cell = cells[p.environment];
        if (cell.isLeaf() || (!rn.isLeaf() && rn.radius >= cellRadius(cell)))
        {
            children[0] = {std::uint32_t(rn.firstChild), p.environment};
            children[1] = {std::uint32_t(rn.firstChild + 1), p.environment};
            return 2;
        }
        for (std::uint32_t k = 0; k < cell.childCount; ++k)
            children[k] = {p.robot, std::uint32_t(cell.firstChild) + k};
        return int(cell.childCount);
    };
    const double best =
        bestFirstDistance(context.scratch<NearestPairQueue>(), lowerBound, isLeafPair, leafDistance, split);
    context.stats.boundingVolumeTests += boxTests;
    context.stats.primitiveTests += triangleTests;
    return best;
}

std::optional<LevelVolumes> OctreeChecker::levelVolumes(int level) const
{
    LevelVolumes v;
    v.kind = "OBB / octree cell";
    v.robotDepth = robotTree_.depth();
    v.environmentDepth = octree_.depth();
    std::vector<std::pair<std::uint32_t, int>> stack;
    if (!robotTree_.empty())
        stack.push_back({0, 0});
    while (!stack.empty())
    {
        const auto [node, depth] = stack.back();
        stack.pop_back();
        const auto &n = robotTree_.nodes()[node];
        if (depth == level || n.isLeaf())
        {
            VolumeTraits<Obb>::appendMesh(n.volume, v.robot);
            continue;
        }
        stack.push_back({std::uint32_t(n.firstChild + 1), depth + 1});
        stack.push_back({std::uint32_t(n.firstChild), depth + 1});
    }
    if (!octree_.empty())
        stack.push_back({0, 0});
    while (!stack.empty())
    {
        const auto [index, depth] = stack.back();
        stack.pop_back();
        const Octree::Cell &c = octree_.cells()[index];
        if (depth == level || c.isLeaf())
        {
            appendMappedCube(v.environment, c.center, c.halfSide * Mat3::Identity());
            continue;
        }
        for (std::uint32_t k = 0; k < c.childCount; ++k)
            stack.push_back({std::uint32_t(c.firstChild) + k, depth + 1});
    }
    return v;
}

std::vector<HierarchyReport> OctreeChecker::hierarchies(bool withVolumeRatios) const
{
    // The label carries the octree's own counts: leaves and triangle references (a triangle is
    // listed in every leaf it touches).
    const std::string octreeLabel = "environment octree (" + std::to_string(octree_.leafCount()) + " leaf cells, " +
                                    std::to_string(octree_.triangleReferences().size()) + " references to " +
                                    std::to_string(scene_.environment->triangleCount()) + " triangles)";
    std::vector<HierarchyReport> reports = {
        {"robot OBB tree", robotTree_.nodes().size(), robotTree_.depth(), robotTree_.buildSeconds(),
         robotTree_.memoryBytes()},
        {octreeLabel, octree_.cells().size(), octree_.depth(), octree_.buildSeconds(),
         octree_.memoryBytes() + environmentTriangleBounds_.capacity() * sizeof(TriangleBounds)}};
    if (withVolumeRatios)
        std::tie(reports[0].meanVolumeRatio, reports[0].ratioNodes) = meanVolumeRatio(robotTree_);
    return reports;
}
}  // namespace hcd
