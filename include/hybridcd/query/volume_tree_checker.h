// SPDX-License-Identifier: BSD-3-Clause
// Checker: a volume tree of the robot against one of the environment, exact triangles at the leaves.
#pragma once

#include "hybridcd/bvh/volume_tree.h"
#include "hybridcd/query/collision_checker.h"

namespace hcd
{
/// Simultaneous descent of two trees, always splitting the node with the larger circumscribed
/// sphere, with an early exit on the first intersecting triangle pair. Each node pair is tested
/// with the spheres first, then the volumes (VolumeTraits<Volume>::overlap, conservative); at the
/// leaves an exact axis-aligned reject, then the exact triangle test. So the answer equals
/// BruteForceChecker's whatever the volume. Instantiated for every volume in volume_traits.h.
template <class Volume>
class VolumeTreeChecker final : public CollisionChecker
{
public:
    VolumeTreeChecker(CollisionScene scene, std::string name, unsigned maxLeafTriangles = 1);
    std::string name() const override { return name_; }
    bool collides(const RigidTransform &worldFromRobot, QueryStats *stats = nullptr) const override;
    double distance(const RigidTransform &worldFromRobot, QueryStats *stats = nullptr) const override;
    bool withinDistance(const RigidTransform &worldFromRobot, double delta, QueryStats *stats = nullptr) const override;
    std::vector<HierarchyReport> hierarchies() const override;

    const VolumeTree<Volume> &robotTree() const { return robotTree_; }
    const VolumeTree<Volume> &environmentTree() const { return environmentTree_; }

private:
    /// Collision (delta = 0, exact triangle test) or proximity (delta > 0) with early exit.
    bool anyPairWithin(const RigidTransform &worldFromRobot, double delta, QueryStats *stats) const;
    double toleranceFor(const RigidTransform &worldFromRobot) const;

    struct TriangleBounds
    {
        Vec3 min, max;
    };

    CollisionScene scene_;
    std::string name_;
    VolumeTree<Volume> robotTree_;
    VolumeTree<Volume> environmentTree_;
    double robotRadius_ = 0.0;
    double environmentMagnitude_ = 0.0;
    std::vector<TriangleBounds> environmentTriangleBounds_;  ///< per mesh triangle, for a cheap exact reject
};

using ObbTreeChecker = VolumeTreeChecker<Obb>;
}  // namespace hcd
