// SPDX-License-Identifier: BSD-3-Clause
// Solid objects: a closed (watertight) mesh component bounds a volume, and containment is contact.
//
// A surface checker answers "do the triangles touch?". When they do not, each connected component
// of one mesh lies entirely inside or entirely outside each closed component of the other, so one
// vertex per component decides the rest: the robot collides when a vertex of any robot component
// lies inside a closed environment component, or (for a closed robot) a vertex of any environment
// component lies inside a closed robot component. Point-in-solid is exact ray parity (SolidQuery),
// which needs no consistent orientation (SketchUp files repeat faces reversed).
#pragma once

#include "hybridcd/bvh/clearance_grid.h"
#include "hybridcd/geometry/solid_components.h"
#include "hybridcd/query/collision_checker.h"

#include <memory>

namespace hcd
{
/// What counts as contact.
enum class ContactSemantics
{
    Solid,        ///< closed components are solids (the default)
    SurfaceOnly,  ///< meshes are surfaces only, as FCL treats them
};

/// Wraps a surface checker with solid semantics; open components stay surfaces.
class SolidSemanticsChecker final : public CollisionChecker
{
public:
    SolidSemanticsChecker(std::unique_ptr<CollisionChecker> surface, const CollisionScene &scene);

    std::string name() const override { return surface_->name(); }
    bool turnsAboutRobotZ() const override { return surface_->turnsAboutRobotZ(); }
    std::vector<HierarchyReport> hierarchies(bool withVolumeRatios = false) const override
    {
        return surface_->hierarchies(withVolumeRatios);
    }
    std::optional<LevelVolumes> levelVolumes(int level) const override { return surface_->levelVolumes(level); }

    /// True when, the surfaces being disjoint, one object lies inside a solid of the other.
    bool contained(const RigidTransform &worldFromRobot) const;

    /// Lets the point-in-solid tests read `grid` first: a clearance grid over this checker's
    /// environment whose cells are labelled with environmentSolids() (GridFirstChecker builds one).
    /// A robot component with one of its probe vertices (up to eight, spread over it) in a cell
    /// proven outside every solid lies outside them all, its surfaces being apart; only the others
    /// take ray parity. Null (the default) goes back to rays alone. The grid must stay alive and
    /// unchanged while this checker answers.
    void useEnvironmentGrid(const ClearanceGrid *grid) { environmentGrid_ = grid; }

    const SolidQuery &environmentSolids() const { return environmentSolids_; }
    const SolidQuery &robotSolids() const { return robotSolids_; }

private:
    bool doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    /// 0 when the surfaces touch or one object is inside the other; otherwise the surface distance.
    double doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    /// A free pose has neither object inside the other: the surface distance alone.
    double doDistanceOfFreePose(const RigidTransform &worldFromRobot, QueryContext &context) const override
    {
        return surface_->distanceOfFreePose(worldFromRobot, context);
    }
    bool doWithinDistance(const RigidTransform &worldFromRobot, double delta, QueryContext &context) const override;
    bool doWithinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                               double robotRadius, QueryContext &context) const override
    {
        if (!worldFromRobot.isFinite())
            return true;
        return surface_->withinSweptDistance(worldFromRobot, translationSlack, radialSlack, robotRadius, context) ||
               contained(worldFromRobot);
    }
    /// The surfaces' pairs; none while one object is inside the other (that pose collides).
    bool doListSweptNearPairs(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                              std::size_t limit, std::vector<TrianglePair> &near, QueryContext &context) const override
    {
        return !contained(worldFromRobot) &&
               surface_->listSweptNearPairs(worldFromRobot, translationSlack, radialSlack, limit, near, context);
    }
    /// Surfaces only: along a motion whose surfaces stay apart, neither object enters the other.
    bool doSweptNearPairsAmong(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                               const std::vector<TrianglePair> &pairs, std::vector<TrianglePair> &near,
                               QueryContext &context) const override
    {
        return surface_->sweptNearPairsAmong(worldFromRobot, translationSlack, radialSlack, pairs, near, context);
    }
    /// The surface contacts, or else a containment record (witness: the contained vertex).
    std::vector<ContactPair> doContacts(const RigidTransform &worldFromRobot, std::size_t limit,
                                        QueryContext &context) const override;

    /// Whether robot component `component` lies inside an environment solid (surfaces apart).
    bool robotComponentInside(const RigidTransform &worldFromRobot, std::size_t component) const;

    std::unique_ptr<CollisionChecker> surface_;
    SolidQuery environmentSolids_;
    SolidQuery robotSolids_;
    std::vector<Vec3> robotRepresentatives_;        ///< one vertex per robot component (robot frame)
    std::vector<Vec3> environmentRepresentatives_;  ///< one vertex per environment component (world)
    std::vector<std::vector<Vec3>> robotProbes_;    ///< up to eight vertices of each robot component (robot frame)
    const ClearanceGrid *environmentGrid_ = nullptr;
};
}  // namespace hcd
