// SPDX-License-Identifier: BSD-3-Clause
// Checker: a volume tree of the robot against one of the environment, exact triangles at the leaves.
#pragma once

#include "hybridcd/bv/box_lanes.h"
#include "hybridcd/bvh/volume_tree.h"
#include "hybridcd/narrowphase/convex_decomposition.h"
#include "hybridcd/query/collision_checker.h"
#include "hybridcd/query/traversal_stack.h"

#include <optional>

namespace hcd
{
struct PlacedTriangle;

/// Simultaneous descent of two trees, splitting the node with the larger circumscribed sphere (both
/// at once where the trees are alike, descendsInLockstep()), with an early exit on the first
/// intersecting triangle pair. Each node pair is tested
/// with the spheres first, then the volumes (VolumeTraits<Volume>::overlap, conservative); at the
/// leaves an exact axis-aligned reject, then the exact triangle test. So the answer equals
/// BruteForceChecker's whatever the volume. OBB and AABB trees test the environment's boxes two
/// levels below a node to split four at a time (SIMD lanes, LanesOf), by the same tests, and the robot's likewise,
/// placed in world once per query. Instantiated for every volume in volume_traits.h. The trees hold each face once
/// (withoutRepeatedFaces); contacts name source-mesh triangles. The LP stage (`--checker lp`): leaves hold up to
/// `leafTriangles` triangles whose convex hull is tested by linear programming before any triangle. Exact mode (no
/// tolerance): an LP "disjoint" rejects the leaf pair, an LP "intersecting" is confirmed by the exact triangle tests.
/// Approximate mode (tolerance T >= 0): a pair of pieces whose approximation bounds (how far any point of a hull may be
/// from its triangles) add up to at most T decides alone, so contact may be reported when the triangles are up to T
/// apart, but is never missed.
struct PieceStage
{
    unsigned leafTriangles = 8;
    std::optional<double> approximateTolerance;
};

/// Medial spheres (`--checker medial`, Volume = MedialSphere): the trees' spheres are moved onto
/// the medial axis of the closed solids after the build (bvh/medial_axis.h). Exact mode (no
/// `leafTolerance`): the spheres only reject, the triangles decide. Approximate mode (tolerance
/// T >= 0): a pair of overlapping leaf spheres whose approximation bounds
/// (MedialSphere::approximationBound) add up to at most T reports collision alone, so a collision
/// is reported only when the solids (or, for open meshes, the triangles) come within T, and never
/// missed; other leaf pairs go to the triangles. Contacts are always exact triangle pairs.
template <class Volume>
class VolumeTreeChecker final : public CollisionChecker
{
public:
    VolumeTreeChecker(CollisionScene scene, std::string name, unsigned maxLeafTriangles = 1,
                      std::optional<PieceStage> pieces = std::nullopt,
                      std::optional<double> leafTolerance = std::nullopt);
    std::string name() const override { return name_; }
    bool turnsAboutRobotZ() const override { return scene_.turnsAboutRobotZ; }
    std::vector<HierarchyReport> hierarchies(bool withVolumeRatios = false) const override;
    std::optional<LevelVolumes> levelVolumes(int level) const override;

    const VolumeTree<Volume> &robotTree() const { return robotTree_; }
    const VolumeTree<Volume> &environmentTree() const { return environmentTree_; }
    /// Whether the traversals split both nodes of a pair at once (trees alike in size: triangle
    /// counts and root spheres within 2x of each other) rather than the larger one.
    bool descendsInLockstep() const { return lockstep_; }
    /// The convex pieces of the LP stage (empty without it).
    const ConvexDecomposition &robotPieces() const { return robotPieces_; }
    const ConvexDecomposition &environmentPieces() const { return environmentPieces_; }

private:
    bool doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    double doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    /// Without the collision pass when the leaves are plain triangles (approximate modes keep it:
    /// their collision answer is not the exact one).
    double doDistanceOfFreePose(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    /// The branch and bound of doDistance, on a pose known free.
    double freeDistance(const RigidTransform &worldFromRobot, QueryContext &context) const;
    bool doWithinDistance(const RigidTransform &worldFromRobot, double delta, QueryContext &context) const override;
    /// Uses each node's and triangle's own reach from the robot origin instead of the robot radius.
    bool doWithinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                               double robotRadius, QueryContext &context) const override;
    std::vector<ContactPair> doContacts(const RigidTransform &worldFromRobot, std::size_t limit,
                                        QueryContext &context) const override;
    /// The swept proximity's traversal without its early exit (plain triangle leaves only).
    bool doListSweptNearPairs(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                              std::size_t limit, std::vector<TrianglePair> &near, QueryContext &context) const override;
    bool doSweptNearPairsAmong(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                               const std::vector<TrianglePair> &pairs, std::vector<TrianglePair> &near,
                               QueryContext &context) const override;

    /// How far a robot part at distance r from the robot origin may be from where the pose puts it.
    struct Slack
    {
        double translation = 0.0;
        double radial = 0.0;
        double at(double r) const { return translation + radial * r; }
    };

    /// Collision (zero slack, exact triangle test) or proximity (distance at most the slack) with
    /// an early exit; with `found`, every contact is recorded (up to `limit`) instead; with `near`,
    /// every triangle pair within the slack, returning true once more than `limit` are.
    bool anyPairWithin(const RigidTransform &worldFromRobot, Slack slack, QueryContext &context,
                       std::vector<ContactPair> *found = nullptr, std::size_t limit = 0,
                       std::vector<TrianglePair> *near = nullptr) const;
    double toleranceFor(const RigidTransform &worldFromRobot) const;
    /// The child pairs of a pair that is not two leaves, in the order to visit them (the larger
    /// node's children, or all four in lockstep); returns their number.
    int childPairs(const NodePair &pair, NodePair *children) const;
    /// Where a pair that is not two leaves is split through lanes, by childPairs' rule: the
    /// environment's block at its environment node, tested against the robot node or, in lockstep,
    /// against each of the robot node's two children; or the robot's block at its robot node. None
    /// where the node split has no block (childPairs splits it then).
    struct LaneSplit
    {
        enum class Kind
        {
            None,
            Environment,
            Robot
        };
        Kind kind = Kind::None;
        const typename LanesOf<Volume>::Type *environmentLanes = nullptr;
        bool eachRobotChild = false;  ///< Environment: against the robot node's two children
        std::size_t robotBlock = 0;   ///< Robot: robotBlocks_[robotBlock]
    };
    LaneSplit laneSplit(const NodePair &pair) const;
    /// The leaf test of every pair query: whether robot triangle rt, placed as `a`, and environment
    /// triangle et touch (no proximity: the exact intersection test) or come within the slack at
    /// rt's reach (proximity), after an exact axis-aligned reject; `tests` counts the exact tests.
    bool trianglePairWithin(const PlacedTriangle &a, std::uint32_t rt, std::uint32_t et, Slack slack, bool proximity,
                            double tolerance, std::uint64_t &tests) const;

    struct TriangleBounds
    {
        Vec3 min, max;
    };

    DistinctFaceMesh robotFaces_, environmentFaces_;  ///< the scene's meshes without repeated faces
    CollisionScene scene_;                            ///< over those meshes
    std::string name_;
    VolumeTree<Volume> robotTree_;
    VolumeTree<Volume> environmentTree_;
    double robotRadius_ = 0.0;
    double environmentMagnitude_ = 0.0;
    std::vector<TriangleBounds> environmentTriangleBounds_;  ///< per mesh triangle, for a cheap exact reject
    std::vector<double>
        robotNodeReach_;  ///< per robot node: max |p| over its volume (robot frame; |(p.x, p.y)| turning about z)
    std::vector<double> robotTriangleReach_;  ///< per robot triangle: max |corner| (or its distance from z)
    std::optional<PieceStage> pieceStage_;
    std::optional<double> leafTolerance_;  ///< approximate mode of the medial spheres
    bool lockstep_ = false;                ///< descendsInLockstep()
    /// Volumes with LanesOf: for each inner environment node at an even depth, the boxes two
    /// levels down (its grandchildren, or a child that is a leaf) as SIMD lanes, at
    /// environmentLanes_[lanesOfNode_[node]] (-1 elsewhere); a pair that splits its environment
    /// node tests them in one call. Empty for other volumes and above kMaxLaneNodes environment
    /// nodes.
    std::vector<typename LanesOf<Volume>::Type> environmentLanes_;
    std::vector<std::int32_t> lanesOfNode_;
    /// The same blocks of the robot tree, by node only (robot nodes two levels below the node at
    /// robotBlocks_[robotBlockOfNode_[node]], and the largest robotNodeReach_ among them); a pair
    /// that splits its robot node places them in world (PlacedRobot::lanes) and tests them at once.
    struct RobotBlock
    {
        std::uint32_t node[4];
        int count;
        double reach;
    };
    std::vector<RobotBlock> robotBlocks_;
    std::vector<std::int32_t> robotBlockOfNode_;
    ConvexDecomposition robotPieces_, environmentPieces_;
};

using ObbTreeChecker = VolumeTreeChecker<Obb>;
}  // namespace hcd
