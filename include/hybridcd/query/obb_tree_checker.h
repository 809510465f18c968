// SPDX-License-Identifier: BSD-3-Clause
// Checker: OBB tree of the robot against OBB tree of the environment, exact triangles at leaves.
#pragma once

#include "hybridcd/bvh/obb_tree.h"
#include "hybridcd/query/collision_checker.h"

namespace hcd
{
/// Simultaneous descent of two OBB trees, always splitting the node with the larger box, with an
/// early exit on the first intersecting triangle pair. The box test is conservative (see
/// obbsOverlap), the leaf test exact, so the answer equals BruteForceChecker's.
class ObbTreeChecker final : public CollisionChecker
{
public:
    explicit ObbTreeChecker(CollisionScene scene, unsigned maxLeafTriangles = 1);
    std::string name() const override { return "obb"; }
    bool collides(const RigidTransform &worldFromRobot, QueryStats *stats = nullptr) const override;
    double distance(const RigidTransform &worldFromRobot, QueryStats *stats = nullptr) const override;
    bool withinDistance(const RigidTransform &worldFromRobot, double delta, QueryStats *stats = nullptr) const override;
    std::vector<HierarchyReport> hierarchies() const override;

private:
    /// Collision (delta = 0, exact triangle test) or proximity (delta > 0) with early exit.
    bool anyPairWithin(const RigidTransform &worldFromRobot, double delta, QueryStats *stats) const;
    double toleranceFor(const RigidTransform &worldFromRobot) const;

    struct TriangleBounds
    {
        Vec3 min, max;
    };

    CollisionScene scene_;
    ObbTree robotTree_;
    ObbTree environmentTree_;
    double robotRadius_ = 0.0;
    double environmentMagnitude_ = 0.0;
    std::vector<TriangleBounds> environmentTriangleBounds_;  ///< per mesh triangle, for a cheap exact reject
};
}  // namespace hcd
