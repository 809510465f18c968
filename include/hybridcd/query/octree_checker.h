// SPDX-License-Identifier: BSD-3-Clause
// Checker: the robot's OBB tree against an octree of the environment, exact triangles at the leaves.
#pragma once

#include "hybridcd/bvh/octree.h"
#include "hybridcd/bvh/volume_tree.h"
#include "hybridcd/query/collision_checker.h"

namespace hcd
{
/// The environment is an octree of its volume (seed §3.1): only cells that touch a triangle exist,
/// and each leaf cell lists the triangles touching it. Robot OBB tree nodes, placed in the world
/// frame, descend against the occupied cells (bounding spheres, then the box separating-axis test,
/// both conservative); a robot leaf against a leaf cell tests its triangles exactly against the
/// cell's. A triangle pair shared by several cells may be tested more than once; contacts are
/// listed once. Surfaces only, like the trees: the catalogue adds solid semantics around it.
class OctreeChecker final : public CollisionChecker
{
public:
    OctreeChecker(CollisionScene scene, std::string name, Octree::Limits limits = {});
    std::string name() const override { return name_; }
    bool turnsAboutRobotZ() const override { return scene_.turnsAboutRobotZ; }
    std::vector<HierarchyReport> hierarchies(bool withVolumeRatios = false) const override;
    /// Robot OBB tree level `level`, and the octree's cells of that depth (or leaves above it).
    std::optional<LevelVolumes> levelVolumes(int level) const override;

    const Octree &octree() const { return octree_; }
    const VolumeTree<Obb> &robotTree() const { return robotTree_; }

private:
    bool doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    double doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    bool doWithinDistance(const RigidTransform &worldFromRobot, double delta, QueryContext &context) const override;
    bool doWithinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                               double robotRadius, QueryContext &context) const override;
    std::vector<ContactPair> doContacts(const RigidTransform &worldFromRobot, std::size_t limit,
                                        QueryContext &context) const override;

    /// A robot part at distance r from the robot origin may be translation + radial * r away.
    struct Slack
    {
        double translation = 0.0;
        double radial = 0.0;
        double at(double r) const { return translation + radial * r; }
    };
    bool anyPairWithin(const RigidTransform &worldFromRobot, Slack slack, QueryContext &context,
                       std::vector<ContactPair> *found = nullptr, std::size_t limit = 0) const;
    double toleranceFor(const RigidTransform &worldFromRobot) const;

    struct TriangleBounds
    {
        Vec3 min, max;
    };

    DistinctFaceMesh robotFaces_, environmentFaces_;  ///< the scene's meshes without repeated faces
    CollisionScene scene_;                            ///< over those meshes
    std::string name_;
    VolumeTree<Obb> robotTree_;
    Octree octree_;
    double robotRadius_ = 0.0;
    double environmentMagnitude_ = 0.0;
    std::vector<TriangleBounds> environmentTriangleBounds_;  ///< per mesh triangle, for a cheap exact reject
    std::vector<double>
        robotNodeReach_;  ///< per robot node: max |p| over its volume (robot frame; |(p.x, p.y)| turning about z)
    std::vector<double> robotTriangleReach_;  ///< per robot triangle: max |corner| (or its distance from z)
};
}  // namespace hcd
