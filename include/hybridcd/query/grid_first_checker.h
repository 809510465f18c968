// SPDX-License-Identifier: BSD-3-Clause
// Checker: a clearance grid of the environment and a sphere cover of the robot first, the wrapped
// exact checker only when they cannot decide.
#pragma once

#include "hybridcd/bv/sphere_cover.h"
#include "hybridcd/bvh/clearance_grid.h"
#include "hybridcd/query/collision_checker.h"
#include "hybridcd/query/solid_semantics_checker.h"

#include <memory>
#include <optional>

namespace hcd
{
struct GridFirstSettings
{
    std::size_t robotSpheres = 32;  ///< leaves of the robot's cover tree (at most 32; twice that for a footprint)
    /// Environment grid cells (1 byte each; 2 with a closed robot and more than eight closed
    /// environment components); a footprint grid gets as many.
    std::size_t maxCells = std::size_t(1) << 20;
    /// Fewer cells when the robot's cover spheres are large: cells as wide as the median leaf
    /// sphere's radius over this (0: always maxCells), but at least kMinimumCells of them.
    double cellsPerLeafRadius = 6.0;
    static constexpr std::size_t kMinimumCells = std::size_t(1) << 15;
    std::size_t maxRobotCells = std::size_t(1) << 17;  ///< the robot's own grid, for a closed robot
};

/// Proofs before the exact checker:
/// - free: a cut of the robot's cover tree (root first, children of a sphere that fails) lies in
///   grid cells whose clearance exceeds its radius (so no robot triangle touches the
///   environment) and, with solid semantics, on the outside of every
///   closed environment solid; for a closed robot, no environment component's first vertex lies
///   within the robot's reach of its origin (so none is inside the robot). Then the robot is free.
/// - free, planar scenes (CollisionScene::planarPoses) and planar poses: the same with circles over
///   the robot's shadow in a footprint grid of the shadows of the environment triangles at the
///   robot's height (buildFootprint), and, with solids, one probe vertex per robot component in a
///   3D cell outside every solid.
/// - colliding (solid semantics only): a robot vertex lies in a free grid cell inside a closed
///   environment solid; or, for a closed robot, the point of an environment triangle nearest a
///   robot cover sphere's centre lies in a free cell of the robot's own grid (robot frame) inside
///   a robot solid. Either is a point of one object inside a solid of the other.
/// - colliding (either semantics): a witness pair of triangles. For each leaf of the robot's cover
///   whose centre falls in an occupied cell, the environment triangle kept for that cell is tested
///   exactly (trianglesIntersect, on the corners as every checker places them) against the robot
///   triangles of that leaf whose vertices are not all on one side of its plane.
/// The two proofs of a collision are optional: each is tried only while it has paid lately in the
/// query's context (ProofOdds), since on some problems one seldom or never decides.
/// Everything else goes to the wrapped checker, which sets the answer, so answers are the wrapped
/// checker's whatever the grid says (tested against bruteforce). Proximity queries use the same
/// proof with each sphere grown by the slack. Distance: 0 on a proved collision; on a proved-free pose
/// the wrapped checker's distance without its collision pass (distanceOfFreePose). Contacts go
/// straight to the wrapped one.
class GridFirstChecker final : public CollisionChecker
{
public:
    /// `exact` answers with `semantics`; the grid is built over `scene.environment`.
    GridFirstChecker(std::unique_ptr<CollisionChecker> exact, const CollisionScene &scene, ContactSemantics semantics,
                     GridFirstSettings settings = {});
    /// Not copied or moved: the wrapped checker reads this one's grid (useEnvironmentGrid).
    GridFirstChecker(const GridFirstChecker &) = delete;
    GridFirstChecker &operator=(const GridFirstChecker &) = delete;

    std::string name() const override { return exact_->name(); }
    std::vector<HierarchyReport> hierarchies(bool withVolumeRatios = false) const override;
    std::optional<LevelVolumes> levelVolumes(int level) const override { return exact_->levelVolumes(level); }

    const ClearanceGrid &grid() const { return grid_; }
    const std::vector<CoverSphere> &robotCover() const { return cover_; }

    /// The grid's own verdict: true proves free, false proves nothing (also for `collidingByGrid`).
    bool freeByGrid(const RigidTransform &worldFromRobot, double translationSlack = 0.0,
                    double radialSlack = 0.0) const;
    bool collidingByGrid(const RigidTransform &worldFromRobot) const;
    bool collidingByWitness(const RigidTransform &worldFromRobot) const;

    /// The footprint grid's cells in a planar scene, else the 3D grid's. A planar scene's proofs
    /// fall back to the coarser 3D grid for poses that are not planar and for sweeps of the robot's
    /// reach or more: those only cost time.
    /// Either layer counting from the axis makes every swept query an SE(2)-only one.
    bool turnsAboutRobotZ() const override { return turnsAboutRobotZ_ || exact_->turnsAboutRobotZ(); }
    double firstLayerCellSize() const override
    {
        return !footprintGrid_.empty() ? footprintGrid_.cellSize() : grid_.empty() ? 0.0 : grid_.cellSize();
    }

private:
    /// The optional proofs' tallies in a context (ProofOddsByChecker).
    static constexpr std::size_t kPointInSolidProof = 0, kWitnessPairProof = 1;
    /// collidingByGrid, then collidingByWitness, each tried only while it pays in this context
    /// (ProofOdds): false proves nothing.
    bool collidingByOptionalProofs(const RigidTransform &worldFromRobot, QueryContext &context) const;
    /// Fills leafStart_ and leafTriangles_ from cover_ and robot_.
    void indexLeafTriangles();
    /// For a planar scene: the footprint grid, the robot's footprint cover and its component probes.
    void buildFootprint(const TriangleMesh &robot, const TriangleMesh &environment, const SolidQuery *robotSolids,
                        std::size_t robotSpheres, std::size_t maxCells);
    /// freeByGrid for a planar pose (rotation about z, no z translation) on the footprint grid;
    /// nullopt when it cannot apply (not planar, or a slack beyond the height margin).
    std::optional<bool> freeByFootprint(const RigidTransform &worldFromRobot, double translationSlack,
                                        double radialSlack) const;
    bool doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    double doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    bool doWithinDistance(const RigidTransform &worldFromRobot, double delta, QueryContext &context) const override;
    bool doWithinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                               double robotRadius, QueryContext &context) const override;
    bool doSweptFreeByFirstLayer(const RigidTransform &worldFromRobot, double translationSlack,
                                 double radialSlack) const override
    {
        return freeByGrid(worldFromRobot, translationSlack, radialSlack);
    }
    std::vector<ContactPair> doContacts(const RigidTransform &worldFromRobot, std::size_t limit,
                                        QueryContext &context) const override
    {
        return exact_->contacts(worldFromRobot, limit, context);
    }
    /// Pairs are the exact checker's: the grid proves whole robot parts, not pairs.
    bool doListSweptNearPairs(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                              std::size_t limit, std::vector<TrianglePair> &near, QueryContext &context) const override
    {
        return exact_->listSweptNearPairs(worldFromRobot, translationSlack, radialSlack, limit, near, context);
    }
    bool doSweptNearPairsAmong(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                               const std::vector<TrianglePair> &pairs, std::vector<TrianglePair> &near,
                               QueryContext &context) const override
    {
        return exact_->sweptNearPairsAmong(worldFromRobot, translationSlack, radialSlack, pairs, near, context);
    }

    std::unique_ptr<CollisionChecker> exact_;
    bool solid_ = true;
    bool robotHasSolids_ = false;
    bool environmentHasSolids_ = false;
    double robotReach_ = 0.0;  ///< max |vertex| of the robot (robot frame)
    /// Swept queries' radial slack counts from the robot's z axis (CollisionScene::turnsAboutRobotZ).
    bool turnsAboutRobotZ_ = false;
    double robotTurnReach_ = 0.0;  ///< robotTurnRadius of the robot: how far a turn moves a point per radian
    std::vector<CoverSphere> cover_;
    ClearanceGrid grid_;
    ClearanceGrid robotGrid_;  ///< the robot's own grid (robot frame), with inside labels; closed robots only
    std::shared_ptr<const TriangleMesh> environment_;  ///< the grid's mesh (each face once)
    std::shared_ptr<const TriangleMesh> robot_;        ///< the robot mesh, each face once (robot frame)
    /// Per cover sphere i, the robot triangles that reach into it: leafTriangles_[leafStart_[i] ..
    /// leafStart_[i + 1]) (empty for inner spheres).
    std::vector<std::uint32_t> leafStart_;
    std::vector<std::uint32_t> leafTriangles_;

    // Planar scenes (CollisionScene::planarPoses). A planar pose keeps every robot point's z, so
    // only environment triangles that reach the robot's height range matter within
    // footprintHeightMargin_ of it; their shadows on z = 0 are at most as far from the robot's
    // shadow as the triangles are from the robot.
    ClearanceGrid footprintGrid_;              ///< planar grid of those triangles' shadows
    std::vector<CoverSphere> footprintCover_;  ///< circles (z = 0, robot frame) over the robot's shadow
    double footprintHeightMargin_ = 0.0;       ///< triangles farther above or below were left out
    double robotHeightReach_ = 0.0;            ///< max |z| of a robot vertex (robot frame)
    /// Per robot component, a few of its vertices: one proved outside every environment solid puts
    /// the whole component outside once no surface comes near it.
    std::vector<std::vector<Vec3>> componentProbes_;
};
}  // namespace hcd
