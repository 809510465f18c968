// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/grid_first_checker.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/query/solid_semantics_checker.h"

#include <algorithm>

namespace hcd
{
GridFirstChecker::GridFirstChecker(std::unique_ptr<CollisionChecker> exact, const CollisionScene &scene,
                                   ContactSemantics semantics, GridFirstSettings settings)
    : exact_(std::move(exact)),
      solid_(semantics == ContactSemantics::Solid)
{
    if (!scene.robot || !scene.environment || scene.robot->empty() || scene.environment->empty())
        return;
    const DistinctFaceMesh robot = withoutRepeatedFaces(scene.robot);
    const DistinctFaceMesh environment = withoutRepeatedFaces(scene.environment);
    cover_ = sphereCover(*robot.mesh, std::clamp<std::size_t>(settings.robotSpheres, 1, 32));
    robotReach_ = scene.robot->radiusAboutOrigin() * (1.0 + 1e-12);
    ClearanceGridSettings gridSettings;
    gridSettings.maxCells = settings.maxCells;
    // Cells around the mesh as wide as the largest cover sphere: a sphere that reaches the mesh has
    // its centre in the grid.
    gridSettings.margin = 0.0;
    for (const CoverSphere &s : cover_)
        if (s.firstChild < 0)
            gridSettings.margin = std::max(gridSettings.margin, s.radius);
    robot_ = robot.mesh;
    environment_ = environment.mesh;
    gridSettings.keepTriangles = true;
    indexLeafTriangles();
    if (solid_)
    {
        // The solid wrapper's indexes when the exact checker is one (as the catalogue makes it):
        // the same solids, found once.
        const auto *wrapper = dynamic_cast<const SolidSemanticsChecker *>(exact_.get());
        const SolidQuery environmentSolids = wrapper ? wrapper->environmentSolids() : SolidQuery(environment.mesh);
        const SolidQuery robotSolids = wrapper ? wrapper->robotSolids() : SolidQuery(robot.mesh);
        robotHasSolids_ = robotSolids.closedComponentCount() > 0;
        environmentHasSolids_ = environmentSolids.closedComponentCount() > 0;
        if (robotHasSolids_)
        {
            ClearanceGridSettings robotSettings;
            robotSettings.maxCells = settings.maxRobotCells;
            robotGrid_ = ClearanceGrid(*robot.mesh, &robotSolids, {}, robotSettings);
        }
        grid_ = ClearanceGrid(*environment.mesh, &environmentSolids,
                              robotHasSolids_ ? firstVertexOfEachComponent(environmentSolids) : std::vector<Vec3>{},
                              gridSettings);
    }
    else
        grid_ = ClearanceGrid(*environment.mesh, nullptr, {}, gridSettings);
}

void GridFirstChecker::indexLeafTriangles()
{
    const TriangleMesh &robot = *robot_;
    leafStart_.assign(cover_.size() + 1, 0);
    for (std::size_t i = 0; i < cover_.size(); ++i)
    {
        leafStart_[i] = std::uint32_t(leafTriangles_.size());
        const CoverSphere &s = cover_[i];
        if (s.firstChild >= 0)
            continue;
        for (std::size_t t = 0; t < robot.triangleCount(); ++t)
        {
            const Vec3 &a = robot.corner(t, 0), &b = robot.corner(t, 1), &c = robot.corner(t, 2);
            const Vec3 low = a.cwiseMin(b).cwiseMin(c), high = a.cwiseMax(b).cwiseMax(c);
            if (((low.array() - s.radius) > s.center.array()).any() ||
                ((high.array() + s.radius) < s.center.array()).any())
                continue;
            if ((closestPointOnTriangle(s.center, a, b, c) - s.center).norm() <= s.radius)
                leafTriangles_.push_back(std::uint32_t(t));
        }
    }
    leafStart_[cover_.size()] = std::uint32_t(leafTriangles_.size());
}

std::vector<HierarchyReport> GridFirstChecker::hierarchies(bool withVolumeRatios) const
{
    std::vector<HierarchyReport> reports = exact_->hierarchies(withVolumeRatios);
    if (!grid_.empty())
    {
        HierarchyReport r;
        const auto cells = grid_.cells();
        r.label = "environment clearance grid " + std::to_string(cells[0]) + "x" + std::to_string(cells[1]) + "x" +
                  std::to_string(cells[2]) + " (" + std::to_string(grid_.occupiedCells()) + " occupied), robot " +
                  std::to_string(cover_.size()) + " spheres";
        r.nodes = std::size_t(cells[0]) * cells[1] * cells[2];
        r.depth = 1;
        r.buildSeconds = grid_.buildSeconds();
        r.memoryBytes = grid_.memoryBytes() + cover_.size() * sizeof(CoverSphere);
        reports.push_back(r);
    }
    return reports;
}

bool GridFirstChecker::freeByGrid(const RigidTransform &worldFromRobot, double translationSlack,
                                  double radialSlack) const
{
    if (grid_.empty() || cover_.empty() || !worldFromRobot.isFinite())
        return false;
    // Rounding of R * c + t, relative to the magnitudes involved.
    const double rounding = 1e-9 * (worldFromRobot.translation.cwiseAbs().maxCoeff() + robotReach_);
    const auto clears = [&](const CoverSphere &s) {
        const ClearanceSample sample = grid_.at(worldFromRobot.apply(s.center));
        // Points of the sphere lie within |c| + r of the robot's origin (no square root for a state).
        const double slack =
            radialSlack > 0.0 ? translationSlack + radialSlack * (s.center.norm() + s.radius) : translationSlack;
        return sample.clearance > s.radius + slack + rounding && (!solid_ || sample.outside);
    };
    // The root sphere holds the whole robot, solid included (a ball is convex): when it clears the
    // surface no environment component can lie inside the robot either.
    if (clears(cover_[0]))
        return true;
    if (solid_ && robotHasSolids_ && !(grid_.at(worldFromRobot.translation).markerClearance > robotReach_ + rounding))
        return false;
    // Depth first over the cover tree: a sphere clear of the surface (and outside every solid)
    // clears its whole subtree; a leaf that is not proves nothing.
    if (cover_[0].firstChild < 0)
        return false;
    int stack[64];
    int size = 0;
    stack[size++] = cover_[0].firstChild + 1;
    stack[size++] = cover_[0].firstChild;
    while (size > 0)
    {
        const CoverSphere &s = cover_[std::size_t(stack[--size])];
        if (clears(s))
            continue;
        if (s.firstChild < 0)
            return false;
        stack[size++] = s.firstChild + 1;
        stack[size++] = s.firstChild;
    }
    return true;
}

bool GridFirstChecker::collidingByGrid(const RigidTransform &worldFromRobot) const
{
    if (!solid_ || grid_.empty() || !worldFromRobot.isFinite())
        return false;
    // Rounding in a mapped point, against how far beyond a free cell its side is known.
    const double rounding = 1e-15 * 8.0 * (worldFromRobot.translation.cwiseAbs().maxCoeff() + robotReach_ + 1.0);
    const auto certainlyInside = [rounding](const ClearanceGrid &grid, const ClearanceSample &s) {
        return s.inside && (rounding < 0.5 * grid.certainMargin() || s.clearance > rounding);
    };
    if (environmentHasSolids_)
        for (const CoverSphere &s : cover_)
            if (s.firstChild < 0 && certainlyInside(grid_, grid_.at(worldFromRobot.apply(s.probe))))
                return true;
    if (!robotGrid_.empty())
    {
        const RigidTransform robotFromWorld = worldFromRobot.inverse();
        const TriangleMesh &env = *environment_;
        for (const CoverSphere &s : cover_)
        {
            if (s.firstChild >= 0)
                continue;
            const Vec3 centre = worldFromRobot.apply(s.center);
            const std::int64_t t = grid_.triangleNear(centre);
            if (t < 0)
                continue;
            const Vec3 onSurface = closestPointOnTriangle(centre, env.corner(std::size_t(t), 0),
                                                          env.corner(std::size_t(t), 1), env.corner(std::size_t(t), 2));
            if (certainlyInside(robotGrid_, robotGrid_.at(robotFromWorld.apply(onSurface))))
                return true;
        }
    }
    return false;
}

bool GridFirstChecker::collidingByWitness(const RigidTransform &worldFromRobot) const
{
    if (grid_.empty() || !environment_ || !worldFromRobot.isFinite())
        return false;
    const TriangleMesh &env = *environment_;
    const TriangleMesh &robot = *robot_;
    const Mat3 &rotation = worldFromRobot.rotation;
    for (std::size_t i = 0; i < cover_.size(); ++i)
    {
        const CoverSphere &s = cover_[i];
        if (s.firstChild >= 0 || leafStart_[i] == leafStart_[i + 1])
            continue;
        const std::int64_t t = grid_.triangleNear(worldFromRobot.apply(s.center));
        if (t < 0)
            continue;
        const Vec3 &b0 = env.corner(std::size_t(t), 0), &b1 = env.corner(std::size_t(t), 1),
                   &b2 = env.corner(std::size_t(t), 2);
        // The plane of the environment triangle in the robot frame, as a filter only: a robot
        // triangle with every vertex clearly on one side cannot meet it. `margin` is far above the
        // rounding in these values, so the filter never drops a triangle the exact test would keep.
        const Vec3 normal = (b1 - b0).cross(b2 - b0);
        const Vec3 robotNormal = rotation.transpose() * normal;
        const double offset = normal.dot(worldFromRobot.translation - b0);
        const double margin =
            1e-9 * normal.norm() *
            (robotReach_ + worldFromRobot.translation.cwiseAbs().maxCoeff() + b0.cwiseAbs().maxCoeff() + 1e-300);
        const Vec3 low = b0.cwiseMin(b1).cwiseMin(b2), high = b0.cwiseMax(b1).cwiseMax(b2);
        for (std::uint32_t k = leafStart_[i]; k < leafStart_[i + 1]; ++k)
        {
            const std::size_t rt = leafTriangles_[k];
            const Vec3 &a0 = robot.corner(rt, 0), &a1 = robot.corner(rt, 1), &a2 = robot.corner(rt, 2);
            const double s0 = robotNormal.dot(a0) + offset, s1 = robotNormal.dot(a1) + offset,
                         s2 = robotNormal.dot(a2) + offset;
            if ((s0 > margin && s1 > margin && s2 > margin) || (s0 < -margin && s1 < -margin && s2 < -margin))
                continue;
            const Vec3 w0 = worldFromRobot.apply(a0), w1 = worldFromRobot.apply(a1), w2 = worldFromRobot.apply(a2);
            if ((w0.cwiseMin(w1).cwiseMin(w2).array() > high.array()).any() ||
                (w0.cwiseMax(w1).cwiseMax(w2).array() < low.array()).any())
                continue;
            if (trianglesIntersect(w0, w1, w2, b0, b1, b2))
                return true;
        }
    }
    return false;
}

bool GridFirstChecker::doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    if (freeByGrid(worldFromRobot))
        return false;
    if (collidingByGrid(worldFromRobot) || collidingByWitness(worldFromRobot))
        return true;
    return exact_->collides(worldFromRobot, context);
}

double GridFirstChecker::doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    // The grid's proofs decide most poses; a proved-free one skips the exact checker's own collision pass.
    if (freeByGrid(worldFromRobot))
        return exact_->distanceOfFreePose(worldFromRobot, context);
    if (collidingByGrid(worldFromRobot) || collidingByWitness(worldFromRobot))
        return 0.0;
    return exact_->distance(worldFromRobot, context);
}

bool GridFirstChecker::doWithinDistance(const RigidTransform &worldFromRobot, double delta, QueryContext &context) const
{
    if (delta >= 0.0 && freeByGrid(worldFromRobot, delta, 0.0))
        return false;
    return exact_->withinDistance(worldFromRobot, delta, context);
}

bool GridFirstChecker::doWithinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack,
                                             double radialSlack, double robotRadius, QueryContext &context) const
{
    if (translationSlack >= 0.0 && radialSlack >= 0.0 && freeByGrid(worldFromRobot, translationSlack, radialSlack))
        return false;
    return exact_->withinSweptDistance(worldFromRobot, translationSlack, radialSlack, robotRadius, context);
}
}  // namespace hcd
