// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/grid_first_checker.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/query/proof_odds.h"
#include "hybridcd/query/solid_semantics_checker.h"

#include <algorithm>
#include <optional>

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
    turnsAboutRobotZ_ = scene.turnsAboutRobotZ;
    robotTurnReach_ = robotTurnRadius(*scene.robot, turnsAboutRobotZ_) * (1.0 + 1e-12);
    ClearanceGridSettings gridSettings;
    gridSettings.maxCells = settings.maxCells;
    // Cells around the mesh as wide as the largest cover sphere: a sphere that reaches the mesh has
    // its centre in the grid.
    gridSettings.margin = 0.0;
    std::vector<double> leafRadii;
    for (const CoverSphere &s : cover_)
        if (s.firstChild < 0)
        {
            gridSettings.margin = std::max(gridSettings.margin, s.radius);
            leafRadii.push_back(s.radius);
        }
    // Cells need not be much finer than the spheres they test: a robot large against the
    // environment (alpha-1.5) gets fewer, which build faster and stay in cache.
    if (settings.cellsPerLeafRadius > 0.0 && !leafRadii.empty())
    {
        const auto middle = leafRadii.begin() + std::ptrdiff_t(leafRadii.size() / 2);
        std::nth_element(leafRadii.begin(), middle, leafRadii.end());
        const double cell = *middle / settings.cellsPerLeafRadius;
        const BoundingBox box = environment.mesh->bounds();
        const Vec3 extent = (box.max - box.min).array() + 2.0 * gridSettings.margin;
        const double wanted = extent.prod() / (cell * cell * cell);
        if (wanted < double(settings.maxCells))
            gridSettings.maxCells =
                std::min(settings.maxCells, std::max(GridFirstSettings::kMinimumCells, std::size_t(wanted)));
    }
    robot_ = robot.mesh;
    environment_ = environment.mesh;
    gridSettings.keepTriangles = true;
    gridSettings.markerReach = robotReach_;  // markers only matter within the robot's reach
    indexLeafTriangles();
    std::optional<SolidQuery> robotSolids;  // with solid semantics, the robot's closed components
    if (solid_)
    {
        // The solid wrapper's indexes when the exact checker is one (as the catalogue makes it):
        // the same solids, found once.
        auto *wrapper = dynamic_cast<SolidSemanticsChecker *>(exact_.get());
        // Solids come from the source meshes, as the wrapper's do: a face repeated in reverse may
        // be shared by two solids (meshComponents()).
        const SolidQuery environmentSolids = wrapper ? wrapper->environmentSolids() : SolidQuery(scene.environment);
        robotSolids = wrapper ? wrapper->robotSolids() : SolidQuery(scene.robot);
        robotHasSolids_ = robotSolids->closedComponentCount() > 0;
        environmentHasSolids_ = environmentSolids.closedComponentCount() > 0;
        if (robotHasSolids_)
        {
            ClearanceGridSettings robotSettings;
            robotSettings.maxCells = settings.maxRobotCells;
            robotGrid_ = ClearanceGrid(*robot.mesh, &*robotSolids, {}, robotSettings);
        }
        grid_ = ClearanceGrid(*environment.mesh, &environmentSolids,
                              robotHasSolids_ ? firstVertexOfEachComponent(environmentSolids) : std::vector<Vec3>{},
                              gridSettings);
        // The wrapper's point-in-solid tests read the grid's labels first (its solids are the ones
        // the cells were labelled with). This checker owns both and is never moved.
        if (wrapper)
            wrapper->useEnvironmentGrid(&grid_);
    }
    else
        grid_ = ClearanceGrid(*environment.mesh, nullptr, {}, gridSettings);
    if (scene.planarPoses)
        buildFootprint(*robot.mesh, *environment.mesh, environmentHasSolids_ ? &*robotSolids : nullptr,
                       settings.robotSpheres, settings.maxCells);
}

void GridFirstChecker::buildFootprint(const TriangleMesh &robot, const TriangleMesh &environment,
                                      const SolidQuery *robotSolids, std::size_t robotSpheres, std::size_t maxCells)
{
    const BoundingBox robotBox = robot.bounds();
    robotHeightReach_ = std::max(std::abs(robotBox.min.z()), std::abs(robotBox.max.z())) * (1.0 + 1e-12);
    // Triangles more than this above or below the robot's height range are left out: proofs whose
    // slack reaches it go to the 3D grid instead.
    footprintHeightMargin_ = robotReach_;
    const double low = robotBox.min.z() - footprintHeightMargin_, high = robotBox.max.z() + footprintHeightMargin_;
    TriangleMesh near;
    near.vertices = environment.vertices;
    for (std::size_t t = 0; t < environment.triangleCount(); ++t)
    {
        const double top =
            std::max({environment.corner(t, 0).z(), environment.corner(t, 1).z(), environment.corner(t, 2).z()});
        const double bottom =
            std::min({environment.corner(t, 0).z(), environment.corner(t, 1).z(), environment.corner(t, 2).z()});
        if (top >= low && bottom <= high)
            near.triangles.push_back(environment.triangles[t]);
    }
    TriangleMesh shadow;
    shadow.triangles = robot.triangles;
    for (const Vec3 &v : robot.vertices)
        shadow.vertices.emplace_back(v.x(), v.y(), 0.0);
    // Twice the 3D cover's leaves: circles are cheap, and smaller ones prove more poses near walls.
    footprintCover_ = sphereCover(shadow, std::clamp<std::size_t>(2 * robotSpheres, 1, 64));
    ClearanceGridSettings settings;
    settings.maxCells = maxCells;
    settings.planar = true;
    for (const CoverSphere &s : footprintCover_)
        if (s.firstChild < 0)
            settings.margin = std::max(settings.margin, s.radius);
    footprintGrid_ = ClearanceGrid(near, nullptr, {}, settings);  // empty without triangles: all clear
    if (!robotSolids)
        return;
    // Eight vertices spread over each component: one of them is likely in a free cell.
    componentProbes_ = verticesSpreadOverEachComponent(*robotSolids, 8);
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

namespace
{
/// One `inspect` line for a grid and the cover tested against it.
HierarchyReport gridReport(const std::string &name, const ClearanceGrid &grid, const std::vector<CoverSphere> &cover,
                           const std::string &coverName)
{
    HierarchyReport r;
    const auto cells = grid.cells();
    r.label = name + " " + std::to_string(cells[0]) + "x" + std::to_string(cells[1]) + "x" + std::to_string(cells[2]) +
              " (" + std::to_string(grid.occupiedCells()) + " occupied), robot " + std::to_string(cover.size()) + " " +
              coverName;
    r.nodes = std::size_t(cells[0]) * cells[1] * cells[2];
    r.depth = 1;
    r.buildSeconds = grid.buildSeconds();
    r.memoryBytes = grid.memoryBytes() + cover.size() * sizeof(CoverSphere);
    return r;
}
}  // namespace

std::vector<HierarchyReport> GridFirstChecker::hierarchies(bool withVolumeRatios) const
{
    std::vector<HierarchyReport> reports = exact_->hierarchies(withVolumeRatios);
    if (!grid_.empty())
        reports.push_back(gridReport("environment clearance grid", grid_, cover_, "spheres"));
    if (!footprintCover_.empty())
        reports.push_back(gridReport("footprint grid", footprintGrid_, footprintCover_, "circles"));
    return reports;
}

namespace
{
/// Whether a cut of the cover tree below its root clears: depth first, a sphere that clears covers
/// its subtree, a leaf that does not proves nothing.
template <class Clears>
bool cutBelowRootClears(const std::vector<CoverSphere> &cover, Clears &&clears)
{
    if (cover[0].firstChild < 0)
        return false;
    // Each pop pushes at most two: the stack never holds more than the tree's depth plus one
    // (covers have at most 64 leaves, so a depth below 64).
    int stack[128];
    int size = 0;
    stack[size++] = cover[0].firstChild + 1;
    stack[size++] = cover[0].firstChild;
    while (size > 0)
    {
        const CoverSphere &s = cover[std::size_t(stack[--size])];
        if (clears(s))
            continue;
        if (s.firstChild < 0)
            return false;
        stack[size++] = s.firstChild + 1;
        stack[size++] = s.firstChild;
    }
    return true;
}

/// A rotation about z and a translation in z = 0, exactly: every point keeps its z, bit for bit.
bool isPlanarPose(const RigidTransform &pose)
{
    const Mat3 &r = pose.rotation;
    return r(2, 2) == 1.0 && r(0, 2) == 0.0 && r(1, 2) == 0.0 && r(2, 0) == 0.0 && r(2, 1) == 0.0 &&
           pose.translation.z() == 0.0;
}
}  // namespace

std::optional<bool> GridFirstChecker::freeByFootprint(const RigidTransform &worldFromRobot, double translationSlack,
                                                      double radialSlack) const
{
    if (footprintCover_.empty() || !isPlanarPose(worldFromRobot))
        return std::nullopt;
    const double rounding = 1e-9 * (worldFromRobot.translation.cwiseAbs().maxCoeff() + robotReach_);
    // Every robot point's slack must stay below the height margin: the triangles left out are
    // farther than that.
    if (!(translationSlack + radialSlack * robotTurnReach_ + rounding < footprintHeightMargin_))
        return std::nullopt;
    const auto clears = [&](const CoverSphere &s) {
        // A robot point over this circle lies within |c| + r of the robot's z axis, and within
        // sqrt((|c| + r)^2 + z^2) of its origin.
        double slack = translationSlack;
        if (radialSlack > 0.0)
        {
            const double planarReach = s.center.norm() + s.radius;
            slack += radialSlack * (turnsAboutRobotZ_
                                        ? planarReach
                                        : std::sqrt(planarReach * planarReach + robotHeightReach_ * robotHeightReach_));
        }
        return footprintGrid_.clears(worldFromRobot.apply(s.center), s.radius + slack + rounding, false);
    };
    if (!clears(footprintCover_[0]) && !cutBelowRootClears(footprintCover_, clears))
        return false;
    if (!solid_)
        return true;
    // No surface comes near: each object is wholly inside or outside each solid of the other.
    if (robotHasSolids_ && !(grid_.at(worldFromRobot.translation).markerClearance > robotReach_ + rounding))
        return false;
    for (const std::vector<Vec3> &probes : componentProbes_)
        if (std::none_of(probes.begin(), probes.end(),
                         [&](const Vec3 &p) { return grid_.at(worldFromRobot.apply(p)).outside; }))
            return false;
    return true;
}

bool GridFirstChecker::freeByGrid(const RigidTransform &worldFromRobot, double translationSlack,
                                  double radialSlack) const
{
    if (grid_.empty() || cover_.empty() || !worldFromRobot.isFinite())
        return false;
    // A planar pose on a planar scene: the footprint decides (it is the finer of the two grids there).
    if (const std::optional<bool> planar = freeByFootprint(worldFromRobot, translationSlack, radialSlack))
        return *planar;
    // Rounding of R * c + t, relative to the magnitudes involved.
    const double rounding = 1e-9 * (worldFromRobot.translation.cwiseAbs().maxCoeff() + robotReach_);
    const auto clears = [&](const CoverSphere &s) {
        // Points of the sphere lie within |c| + r of the robot's origin, and within |(c.x, c.y)| + r
        // of its z axis (no square root for a state).
        const double reach = turnReach(s.center, turnsAboutRobotZ_) + s.radius;
        const double slack = radialSlack > 0.0 ? translationSlack + radialSlack * reach : translationSlack;
        return grid_.clears(worldFromRobot.apply(s.center), s.radius + slack + rounding, solid_);
    };
    // The root sphere holds the whole robot, solid included (a ball is convex): when it clears the
    // surface no environment component can lie inside the robot either.
    if (clears(cover_[0]))
        return true;
    if (solid_ && robotHasSolids_ && !(grid_.at(worldFromRobot.translation).markerClearance > robotReach_ + rounding))
        return false;
    // A cut of the cover tree: a sphere clear of the surface (and outside every solid) clears its
    // whole subtree.
    return cutBelowRootClears(cover_, clears);
}

bool GridFirstChecker::collidingByGrid(const RigidTransform &worldFromRobot) const
{
    if (!solid_ || grid_.empty() || !worldFromRobot.isFinite())
        return false;
    // Rounding in a mapped point, against how far beyond a free cell its side is known.
    const double rounding = 1e-15 * 8.0 * (worldFromRobot.translation.cwiseAbs().maxCoeff() + robotReach_ + 1.0);
    if (environmentHasSolids_)
        for (const CoverSphere &s : cover_)
            if (s.firstChild < 0 && grid_.certainlyInside(worldFromRobot.apply(s.probe), rounding))
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
            if (robotGrid_.certainlyInside(robotFromWorld.apply(onSurface), rounding))
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

bool GridFirstChecker::collidingByOptionalProofs(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    // How often each proof settles the poses the grid leaves undecided depends on the problem: on
    // some most, on others none, at a cost each miss wastes (the witness pair tests every cover
    // sphere's kept triangle; bench/README.md, section 1, "Optional proofs while they pay").
    ProofOddsByChecker::Tallies &odds = context.scratch<ProofOddsByChecker>().of(this);
    return odds[kPointInSolidProof].attempt([&] { return collidingByGrid(worldFromRobot); }) ||
           odds[kWitnessPairProof].attempt([&] { return collidingByWitness(worldFromRobot); });
}

bool GridFirstChecker::doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    if (freeByGrid(worldFromRobot))
        return false;
    if (collidingByOptionalProofs(worldFromRobot, context))
        return true;
    return exact_->collides(worldFromRobot, context);
}

double GridFirstChecker::doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    // The grid's proofs decide most poses; a proved-free one skips the exact checker's own collision pass.
    if (freeByGrid(worldFromRobot))
        return exact_->distanceOfFreePose(worldFromRobot, context);
    if (collidingByOptionalProofs(worldFromRobot, context))
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
