// SPDX-License-Identifier: BSD-3-Clause
// The reference checker: every triangle pair whose bounding boxes overlap is tested exactly.
#pragma once

#include "hybridcd/query/collision_checker.h"

namespace hcd
{
/// The answer every faster checker is tested against. No hierarchy and no rounding in its culling:
/// per query it maps all robot triangles to world, computes each triangle's axis-aligned box with
/// exact comparisons, enumerates all robot/environment pairs whose boxes overlap by one sweep along
/// x, and runs the exact triangle test on each. Only pairs that cannot touch are skipped. A face
/// repeated in a mesh (withoutRepeatedFaces) is tested once; contacts name source-mesh triangles.
class BruteForceChecker final : public CollisionChecker
{
public:
    explicit BruteForceChecker(CollisionScene scene);
    std::string name() const override { return "bruteforce"; }

private:
    bool doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    double doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    std::vector<ContactPair> doContacts(const RigidTransform &worldFromRobot, std::size_t limit,
                                        QueryContext &context) const override;

    struct TriangleBox
    {
        Vec3 min, max;
        std::uint32_t triangle;
    };
    DistinctFaceMesh robotFaces_, environmentFaces_;
    CollisionScene scene_;                       ///< over the meshes without repeated faces
    std::vector<TriangleBox> environmentBoxes_;  ///< sorted by min.x
};
}  // namespace hcd
