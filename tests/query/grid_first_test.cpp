// SPDX-License-Identifier: BSD-3-Clause
// The clearance grid and the grid-first checker against independent references: point-to-mesh
// distance and point-in-solid by brute force for the grid; bruteforce for every verdict of the
// checker, and each of its two proofs (free, colliding) checked alone, on OMPL.app problems and on
// adversarial scenes (containment both ways, touching faces, thin walls, huge and tiny scales).
#include "support/test_support.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/query/brute_force_checker.h"
#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/query/grid_first_checker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

using namespace hcd;

namespace
{
double pointMeshDistance(const TriangleMesh &mesh, const Vec3 &p)
{
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        best = std::min(
            best, (closestPointOnTriangle(p, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)) - p).norm());
    return best;
}

void append(TriangleMesh &into, const TriangleMesh &part)
{
    const auto offset = std::uint32_t(into.vertices.size());
    into.vertices.insert(into.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (const auto &t : part.triangles)
        into.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

/// Closed boxes and a few open, slanted triangles: solids and surfaces, thin walls among them.
TriangleMesh clutter(test::TestRandom &rng, double scale)
{
    std::uniform_real_distribution<double> u(-1.0, 1.0), size(0.02, 0.4);
    TriangleMesh mesh;
    for (int i = 0; i < 12; ++i)
    {
        const Vec3 c(u(rng), u(rng), u(rng));
        Vec3 half(size(rng), size(rng), size(rng));
        if (i % 4 == 0)
            half[i % 3] = 1e-3;  // a thin wall
        append(mesh, test::boxMesh(scale * (c - half), scale * (c + half)));
    }
    for (int i = 0; i < 6; ++i)
    {
        const auto first = std::uint32_t(mesh.vertices.size());
        const Vec3 c(u(rng), u(rng), u(rng));
        for (int k = 0; k < 3; ++k)
            mesh.vertices.push_back(scale * (c + 0.5 * Vec3(u(rng), u(rng), u(rng))));
        mesh.triangles.push_back({first, first + 1, first + 2});
    }
    return mesh;
}

std::shared_ptr<const TriangleMesh> shared(TriangleMesh mesh)
{
    return std::make_shared<const TriangleMesh>(std::move(mesh));
}

RigidTransform randomPose(test::TestRandom &rng, double extent)
{
    std::uniform_real_distribution<double> u(-extent, extent);
    return {test::randomRotation(rng), Vec3(u(rng), u(rng), u(rng))};
}

/// ClearanceGrid::clears, the square-root-free test, against at(): it never clears where at() does
/// not, and clears wherever at() does by more than rounding.
void expectClearsAgreesWithAt(const ClearanceGrid &grid, const Vec3 &p, const ClearanceSample &s, double scale)
{
    for (const double reach : {0.0, 0.5 * s.clearance, s.clearance, 0.999999 * s.clearance, 2.0 * s.clearance})
        for (const bool outside : {false, true})
        {
            const bool byAt = s.clearance > reach && (!outside || s.outside);
            const bool byClears = grid.clears(p, reach, outside);
            if (byClears)
                ASSERT_TRUE(byAt) << "point " << p.transpose() << " reach " << reach;
            if (s.clearance > reach * (1.0 + 1e-9) + 1e-9 * scale && (!outside || s.outside))
                ASSERT_TRUE(byClears) << "point " << p.transpose() << " reach " << reach;
        }
}

// certainlyInside(), read from a bit per cell, is at()'s inside with its clearance above the
// rounding unless the rounding is below half the certain margin.
void expectCertainlyInsideAgreesWithAt(const ClearanceGrid &grid, const Vec3 &p, const ClearanceSample &s, double scale)
{
    for (const double rounding : {0.0, 0.25 * grid.certainMargin(), grid.certainMargin(), 0.5 * s.clearance,
                                  s.clearance, 2.0 * s.clearance + 1e-3 * scale})
    {
        const bool byAt = s.inside && (rounding < 0.5 * grid.certainMargin() || s.clearance > rounding);
        ASSERT_EQ(grid.certainlyInside(p, rounding), byAt) << "point " << p.transpose() << " rounding " << rounding;
    }
}

struct Verdicts
{
    int freeProved = 0, collidingProved = 0, witnessProved = 0, free = 0, colliding = 0;
};

/// Every answer of the grid-first checker equals bruteforce's; each proof alone is never wrong.
Verdicts expectAgreement(const CollisionScene &scene, ContactSemantics semantics,
                         const std::vector<RigidTransform> &poses)
{
    CheckerOptions exactOnly;
    exactOnly.semantics = semantics;
    exactOnly.clearanceGrid = false;
    CheckerOptions withGrid = exactOnly;
    withGrid.clearanceGrid = true;
    const auto reference = makeChecker("bruteforce", scene, exactOnly);
    const auto checker = makeChecker("obb", scene, withGrid);
    const auto *grid = dynamic_cast<const GridFirstChecker *>(checker.get());
    EXPECT_NE(grid, nullptr) << "obb should come with its grid first";
    Verdicts v;
    if (!grid)
        return v;
    QueryContext context;
    std::size_t index = 0;
    for (const RigidTransform &pose : poses)
    {
        const bool truth = reference->collides(pose);
        EXPECT_EQ(checker->collides(pose, context), truth);
        // Distance through the grid's proofs (0 on a proved collision, no collision pass on a
        // proved-free pose), bit for bit, on every fourth pose (the reference is quadratic).
        if (index++ % 4 == 0)
            EXPECT_EQ(checker->distance(pose, context), reference->distance(pose));
        const bool freeProved = grid->freeByGrid(pose);
        const bool collidingProved = grid->collidingByGrid(pose);
        const bool witnessProved = grid->collidingByWitness(pose);
        EXPECT_FALSE(freeProved && truth) << "the grid proved a colliding pose free";
        EXPECT_FALSE(collidingProved && !truth) << "the grid proved a free pose colliding";
        EXPECT_FALSE(witnessProved && !truth) << "a witness pair was found at a free pose";
        v.freeProved += freeProved;
        v.collidingProved += collidingProved;
        v.witnessProved += witnessProved;
        (truth ? v.colliding : v.free) += 1;
        if (!truth)
        {
            // Proximity: "not within delta" only when the distance exceeds delta.
            const double d = reference->distance(pose);
            for (double delta : {0.25 * d, 0.9 * d, 1.1 * d})
                if (!grid->freeByGrid(pose, delta, 0.0))
                    continue;
                else
                    EXPECT_GT(d, delta);
            // "Within" may be answered conservatively at distances near rounding.
            if (d > 1e-6 * scene.robot->radiusAboutOrigin())
                EXPECT_EQ(checker->withinDistance(pose, 0.5 * d, context), false);
            EXPECT_EQ(checker->withinDistance(pose, 1.01 * d, context), true);
        }
    }
    return v;
}
}  // namespace

TEST(ClearanceGrid, BoundsAreLowerBoundsAndSidesAreExact)
{
    test::TestRandom rng(test::seeded(11));
    for (double scale : {1e-6, 1.0, 1e6})
    {
        const auto mesh = shared(clutter(rng, scale));
        const SolidQuery solids(mesh);
        ASSERT_GT(solids.closedComponentCount(), 0u);
        std::vector<Vec3> markers;
        for (const MeshComponent &c : solids.components())
            markers.push_back(mesh->corner(c.triangles.front(), 0));
        ClearanceGridSettings settings;
        settings.maxCells = 1 << 15;
        settings.margin = 0.3 * scale;
        const ClearanceGrid grid(*mesh, &solids, markers, settings);  // 12 markers: kept per cell
        // Three markers: kept as points and measured to directly.
        const std::vector<Vec3> fewMarkers(markers.begin(), markers.begin() + 3);
        const ClearanceGrid fewMarkerGrid(*mesh, &solids, fewMarkers, settings);
        // Marker distances wanted only up to `reach`: the transform stops a few cells beyond it.
        ClearanceGridSettings reachSettings = settings;
        reachSettings.markerReach = 0.2 * scale;
        const ClearanceGrid reachGrid(*mesh, &solids, markers, reachSettings);
        // Without the point-in-solid query no cell is labelled: nothing is certainly inside.
        const ClearanceGrid unlabelled(*mesh, nullptr, markers, settings);
        ASSERT_GT(markers.size(), 8u);
        int fewMarkersNear = 0, beyondReach = 0, cappedBelow = 0;
        std::uniform_real_distribution<double> u(-1.6, 1.6), far(-4.0, 4.0);
        // A fixed count (cheap even under the sanitizers): the "not vacuous" checks below need it.
        // One point in four may lie beyond the grid (which ends 0.3 past the mesh's box); another
        // one in four is drawn inside some solid (the first of up to 50 draws that is), so that
        // points inside solids are seen whatever the seed.
        constexpr int kPoints = 3000;
        int insideSeen = 0, outsideSeen = 0, positiveSeen = 0;
        for (int i = 0; i < kPoints; ++i)
        {
            Vec3 p = i % 4 == 0 ? scale * Vec3(far(rng), far(rng), far(rng)) : scale * Vec3(u(rng), u(rng), u(rng));
            for (int draw = 0; i % 4 == 1 && draw < 50 && !solids.insideAnySolid(p); ++draw)
                p = scale * Vec3(u(rng), u(rng), u(rng));
            const ClearanceSample s = grid.at(p);
            const double d = pointMeshDistance(*mesh, p);
            ASSERT_LE(s.clearance, d) << "scale " << scale << " point " << p.transpose();
            double markerDistance = std::numeric_limits<double>::infinity();
            for (const Vec3 &m : markers)
                markerDistance = std::min(markerDistance, (m - p).norm());
            ASSERT_LE(s.markerClearance, markerDistance);
            double fewMarkerDistance = std::numeric_limits<double>::infinity();
            for (const Vec3 &m : fewMarkers)
                fewMarkerDistance = std::min(fewMarkerDistance, (m - p).norm());
            const ClearanceSample few = fewMarkerGrid.at(p);
            ASSERT_LE(few.markerClearance, fewMarkerDistance);
            // Not vacuous: within rounding of the distance itself.
            ASSERT_GE(few.markerClearance, fewMarkerDistance - 1e-6 * scale);
            fewMarkersNear += fewMarkerDistance < 0.5 * scale;
            // Capped at the reach: still a lower bound, and still beyond the reach where the
            // markers are more than five cells farther.
            const ClearanceSample capped = reachGrid.at(p);
            ASSERT_LE(capped.markerClearance, markerDistance);
            if (markerDistance > reachSettings.markerReach + 5.0 * reachGrid.cellSize())
            {
                ASSERT_GT(capped.markerClearance, reachSettings.markerReach) << "point " << p.transpose();
                ++beyondReach;
            }
            cappedBelow += capped.markerClearance < s.markerClearance;
            ASSERT_EQ(capped.clearance, s.clearance);
            // The marker channel is all that differs.
            ASSERT_EQ(few.clearance, s.clearance);
            ASSERT_EQ(few.inside, s.inside);
            ASSERT_EQ(few.outside, s.outside);
            expectClearsAgreesWithAt(grid, p, s, scale);
            expectCertainlyInsideAgreesWithAt(grid, p, s, scale);
            ASSERT_FALSE(unlabelled.certainlyInside(p, 0.0));
            ASSERT_FALSE(s.inside && s.outside);
            if (s.inside)
                ASSERT_TRUE(solids.insideAnySolid(p));
            if (s.outside)
                ASSERT_FALSE(solids.insideAnySolid(p));
            insideSeen += s.inside;
            outsideSeen += s.outside;
            positiveSeen += s.clearance > 0.0;
        }
        // The bounds are not vacuous: the grid decides most points of this scene.
        EXPECT_GT(insideSeen, 10) << "scale " << scale;
        EXPECT_GT(outsideSeen, kPoints / 2) << "scale " << scale;
        EXPECT_GT(positiveSeen, kPoints / 2) << "scale " << scale;
        EXPECT_GT(fewMarkersNear, 10) << "scale " << scale;
        EXPECT_GT(beyondReach, 10) << "scale " << scale;
        EXPECT_GT(cappedBelow, 10) << "scale " << scale;  // the cap is applied
        for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()})
            EXPECT_FALSE(grid.certainlyInside(Vec3(bad, 0.0, 0.0), 0.0));
    }
}

TEST(ClearanceGrid, PointsOnTheSurfaceGetNoClearanceAndNoSide)
{
    const auto mesh = shared(test::boxMesh(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
    const SolidQuery solids(mesh);
    const ClearanceGrid grid(*mesh, &solids, {}, {});
    for (const Vec3 &p : {Vec3(1, 0.3, -0.2), Vec3(-1, -1, -1), Vec3(0.5, 1, 1), Vec3(0.99999999999, 0, 0)})
    {
        const ClearanceSample s = grid.at(p);
        EXPECT_EQ(s.clearance, 0.0);
        EXPECT_FALSE(s.outside);
        EXPECT_FALSE(s.inside);
    }
    EXPECT_TRUE(grid.at(Vec3(0, 0, 0)).inside);
    EXPECT_TRUE(grid.at(Vec3(5, 0, 0)).outside);
    EXPECT_NEAR(grid.at(Vec3(5, 0, 0)).clearance, 4.0, 1e-6);  // beyond the grid: the box distance
}

TEST(GridFirst, AgreesWithBruteForceInClutterAtEveryScale)
{
    test::TestRandom rng(test::seeded(12));
    for (double scale : {1e-6, 1.0, 1e6})
        for (ContactSemantics semantics : {ContactSemantics::Solid, ContactSemantics::SurfaceOnly})
        {
            CollisionScene scene;
            scene.environment = shared(clutter(rng, scale));
            TriangleMesh robot = test::boxMesh(scale * Vec3(-0.15, -0.04, -0.04), scale * Vec3(0.15, 0.04, 0.04));
            append(robot, test::boxMesh(scale * Vec3(0.1, -0.1, -0.02), scale * Vec3(0.14, 0.1, 0.02)));
            scene.robot = shared(robot);
            std::vector<RigidTransform> poses;
            for (int i = 0; i < test::cases(600); ++i)
            {
                RigidTransform p = randomPose(rng, 1.3);
                p.translation *= scale;
                poses.push_back(p);
            }
            const Verdicts v = expectAgreement(scene, semantics, poses);
            EXPECT_GT(v.freeProved, v.free / 4) << "scale " << scale;
            if (v.colliding >= 20)
                EXPECT_GT(v.witnessProved, v.colliding / 4) << "scale " << scale;
            if (semantics == ContactSemantics::Solid)
                EXPECT_GT(v.collidingProved, 0) << "scale " << scale;
            else
                EXPECT_EQ(v.collidingProved, 0);
        }
}

TEST(GridFirst, ContainmentBothWaysAndTouchingFaces)
{
    // A closed robot box around a small environment box (the environment inside the robot), the
    // robot inside a large closed box, and faces that touch exactly.
    CollisionScene scene;
    TriangleMesh environment = test::boxMesh(Vec3(-0.05, -0.05, -0.05), Vec3(0.05, 0.05, 0.05));
    append(environment, test::boxMesh(Vec3(2, -3, -3), Vec3(8, 3, 3)));
    scene.environment = shared(environment);
    scene.robot = shared(test::boxMesh(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
    std::vector<RigidTransform> poses;
    for (double x : {0.0, 0.9, 0.94, 0.95, 0.96, 1.05, 1.0500001, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 9.0000001, 12.0})
        poses.push_back({Mat3::Identity(), Vec3(x, 0, 0)});
    test::TestRandom rng(test::seeded(13));
    for (int i = 0; i < test::cases(300); ++i)
        poses.push_back(randomPose(rng, 10.0));
    const Verdicts v = expectAgreement(scene, ContactSemantics::Solid, poses);
    EXPECT_GT(v.colliding, 0);
    EXPECT_GT(v.collidingProved, 0);  // the robot at x = 5: its vertices inside the large box
    EXPECT_GT(v.freeProved, 0);
}

// An L-shaped closed prism and a closed robot box of the same height: the robot's vertices are
// level with the prism's top and bottom faces, where the +x ray of the point-in-solid test runs in
// a face's plane and falls back to generic rays, and in the L's concavity the robot is inside the
// solid's box but outside the solid. Containment is read from the grid's labels first there
// (SolidSemanticsChecker::useEnvironmentGrid); the verdicts are bruteforce's. A shorter robot
// inside an arm of the L touches none of its faces: colliding by containment alone.
TEST(GridFirst, ContainmentInAConcaveSolidAtTheRobotsOwnHeight)
{
    TriangleMesh prism;
    const double outline[6][2] = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
    for (const double z : {1.0, -1.0})
        for (const auto &xy : outline)
            prism.vertices.emplace_back(xy[0], xy[1], z);
    for (std::uint32_t k = 1; k + 1 < 6; ++k)  // the L is star-shaped about its corner 0
    {
        prism.triangles.push_back({0, k, k + 1});
        prism.triangles.push_back({6, 7 + k, 6 + k});
    }
    for (std::uint32_t k = 0; k < 6; ++k)
    {
        const std::uint32_t n = (k + 1) % 6;
        prism.triangles.push_back({k, 6 + k, 6 + n});
        prism.triangles.push_back({k, 6 + n, n});
    }
    for (const double height : {1.0, 0.5})
    {
        SCOPED_TRACE(height);
        CollisionScene scene;
        scene.environment = shared(prism);
        scene.robot = shared(test::boxMesh(Vec3(-0.2, -0.2, -height), Vec3(0.2, 0.2, height)));
        ASSERT_EQ(SolidQuery(scene.environment).closedComponentCount(), 1u);
        std::vector<RigidTransform> poses;
        for (const auto &[x, y] : {std::pair{0.5, 2.0}, {2.0, 0.5}, {2.0, 2.0}, {1.5, 1.5}, {1.0, 2.0}, {1.21, 2.0}})
            for (const double yaw : {0.0, 0.4})
                poses.push_back(RigidTransform::fromPlanarPose(x, y, yaw));
        test::TestRandom rng(test::seeded(19));
        std::uniform_real_distribution<double> u(-0.5, 3.5), turn(-M_PI, M_PI);
        for (int i = 0; i < test::cases(400); ++i)
            poses.push_back(RigidTransform::fromPlanarPose(u(rng), u(rng), turn(rng)));
        const Verdicts v = expectAgreement(scene, ContactSemantics::Solid, poses);
        EXPECT_GT(v.colliding, 20);
        EXPECT_GT(v.free, 20);
        const auto brute = makeChecker("bruteforce", scene);
        EXPECT_TRUE(brute->collides(RigidTransform::fromPlanarPose(0.5, 2.0, 0.0)));   // in an arm
        EXPECT_FALSE(brute->collides(RigidTransform::fromPlanarPose(2.0, 2.0, 0.0)));  // in the concavity
        // The wrapper alone (the grid's own proofs would settle many of these first): containment
        // with the grid's labels equals ray parity alone wherever the surfaces are apart.
        CheckerOptions surfaceOnly;
        surfaceOnly.semantics = ContactSemantics::SurfaceOnly;
        surfaceOnly.clearanceGrid = false;
        const auto surfaces = makeChecker("obb", scene, surfaceOnly);
        SolidSemanticsChecker rays(makeChecker("obb", scene, surfaceOnly), scene);
        SolidSemanticsChecker labels(makeChecker("obb", scene, surfaceOnly), scene);
        ClearanceGridSettings settings;
        settings.margin = 0.5;
        const ClearanceGrid grid(*scene.environment, &labels.environmentSolids(), {}, settings);
        labels.useEnvironmentGrid(&grid);
        int inside = 0, outside = 0;
        for (const RigidTransform &pose : poses)
        {
            if (surfaces->collides(pose))
                continue;
            const bool contained = rays.contained(pose);
            EXPECT_EQ(labels.contained(pose), contained);
            (contained ? inside : outside) += 1;
        }
        EXPECT_GT(outside, 20);
        if (height < 1.0)
            EXPECT_GT(inside, 0);
    }
}

TEST(GridFirst, AgreesWithBruteForceOnOmplAppProblems)
{
    for (const char *name : {"3D/Home.cfg", "3D/Abstract.cfg", "2D/Maze_planar.cfg", "3D/bugtrap.cfg"})
    {
        const auto path = test::omplappProblem(name);
        if (!path)
            HYBRIDCD_SKIP_OR_FAIL_IN_CI("OMPL.app resources not found; set HYBRIDCD_OMPLAPP_RESOURCES");
        const LoadedProblem problem = loadProblem(*path);
        test::TestRandom rng(test::seeded(14));
        const Verdicts v = expectAgreement(problem.scene, ContactSemantics::Solid,
                                           test::randomPoses(problem, std::size_t(test::cases(160)), rng));
        EXPECT_GT(v.freeProved + v.collidingProved, 0) << name;
        if (v.colliding >= 20)
            EXPECT_GT(v.witnessProved, v.colliding / 4) << name;
    }
}

TEST(GridFirst, SweptProximityProofsHoldAlongTheSweep)
{
    // withinSweptDistance false must mean: no robot point p comes within t + r |p| of the
    // environment. Checked with the exact distance: distance > t + r * (robot radius) suffices
    // for the robot's reach, so a proof is compared with the tighter exact bound per vertex too.
    CollisionScene scene;
    test::TestRandom rng(test::seeded(15));
    scene.environment = shared(clutter(rng, 1.0));
    scene.robot = shared(test::boxMesh(Vec3(-0.1, -0.05, -0.05), Vec3(0.2, 0.05, 0.05)));
    const auto reference = makeChecker("bruteforce", scene);
    const auto checker = makeChecker("obb", scene);
    const auto *grid = dynamic_cast<const GridFirstChecker *>(checker.get());
    ASSERT_NE(grid, nullptr);
    int proved = 0;
    for (int i = 0; i < test::cases(400); ++i)
    {
        const RigidTransform pose = randomPose(rng, 1.3);
        const double slack = 0.02 * (i % 5), radial = 0.05 * (i % 3);
        // The public first word on swept proximity is the grid's proof; checkers without a first
        // layer prove nothing.
        ASSERT_EQ(checker->sweptFreeByFirstLayer(pose, slack, radial), grid->freeByGrid(pose, slack, radial));
        ASSERT_FALSE(reference->sweptFreeByFirstLayer(pose, slack, radial));
        if (!grid->freeByGrid(pose, slack, radial))
            continue;
        ++proved;
        // Every robot point p is within 0.25 of the origin here; the exact distance must exceed
        // the largest slack any point may have.
        const double reach = scene.robot->radiusAboutOrigin();
        EXPECT_GT(reference->distance(pose), slack + radial * reach - 1e-12) << i;
    }
    EXPECT_GT(proved, 20);
    EXPECT_GT(checker->firstLayerCellSize(), 0.0);
    EXPECT_EQ(reference->firstLayerCellSize(), 0.0);
    // Slacks that are negative or not numbers prove nothing.
    const RigidTransform far{Mat3::Identity(), Vec3(50, 50, 50)};
    EXPECT_TRUE(checker->sweptFreeByFirstLayer(far, 0.01, 0.01));
    for (const auto &[t, r] : std::vector<std::pair<double, double>>{
             {-0.01, 0.0}, {0.0, -0.01}, {std::nan(""), 0.0}, {0.0, std::numeric_limits<double>::infinity()}})
        EXPECT_FALSE(checker->sweptFreeByFirstLayer(far, t, r)) << t << " " << r;
}

TEST(GridFirst, AnOpenSheetThroughAClosedRobotIsProvedColliding)
{
    // The environment is one open sheet (no solid); the robot a closed box. Where the sheet cuts
    // the box, a point of the sheet lies inside the robot: the robot's own grid proves it.
    CollisionScene scene;
    TriangleMesh sheet;
    sheet.vertices = {Vec3(-10, -10, 0), Vec3(10, -10, 0), Vec3(10, 10, 0), Vec3(-10, 10, 0)};
    sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
    scene.environment = shared(sheet);
    scene.robot = shared(test::boxMesh(Vec3(-1, -0.5, -0.5), Vec3(1, 0.5, 0.5)));
    std::vector<RigidTransform> poses;
    test::TestRandom rng(test::seeded(16));
    std::uniform_real_distribution<double> u(-3.0, 3.0), lift(-1.5, 1.5);
    // A fixed count (two sheet triangles: cheap under the sanitizers too); the rates below need it.
    for (int i = 0; i < 400; ++i)
        poses.push_back({test::randomRotation(rng), Vec3(u(rng), u(rng), lift(rng))});
    for (double z : {0.0, 0.2, 0.49, 0.5, 0.5000000001, 0.51})
        poses.push_back({Mat3::Identity(), Vec3(0, 0, z)});
    const Verdicts v = expectAgreement(scene, ContactSemantics::Solid, poses);
    // Only spheres whose centre's cell the sheet marks look for a sheet point: a fifth at least.
    EXPECT_GT(v.collidingProved, v.colliding / 5);
    EXPECT_GT(v.freeProved, v.free / 2);
}

namespace
{
TriangleMesh shadowOf(const TriangleMesh &mesh)
{
    TriangleMesh shadow = mesh;
    for (Vec3 &v : shadow.vertices)
        v.z() = 0.0;
    return shadow;
}

/// An upright triangle standing on the segment from a to b (z from `low` to `high`): its shadow is
/// a slanted segment.
TriangleMesh uprightTriangle(const Vec3 &a, const Vec3 &b, double low, double high)
{
    TriangleMesh t;
    t.vertices = {Vec3(a.x(), a.y(), low), Vec3(b.x(), b.y(), low), Vec3(a.x(), a.y(), high)};
    t.triangles = {{0, 1, 2}};
    return t;
}
/// clutter() and six upright triangles on random segments: shadows that are segments.
TriangleMesh clutterWithUprightFaces(test::TestRandom &rng, double scale)
{
    TriangleMesh mesh = clutter(rng, scale);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 6; ++i)
        append(mesh, uprightTriangle(scale * Vec3(u(rng), u(rng), 0), scale * Vec3(u(rng), u(rng), 0), scale * u(rng),
                                     scale * (1.0 + u(rng))));
    return mesh;
}
}  // namespace

TEST(ClearanceGrid, PlanarBoundsAreLowerBoundsOnShadowDistances)
{
    test::TestRandom rng(test::seeded(17));
    for (double scale : {1e-6, 1.0, 1e6})
    {
        TriangleMesh mesh = clutterWithUprightFaces(rng, scale);
        ClearanceGridSettings settings;
        settings.maxCells = 1 << 14;
        settings.margin = 0.3 * scale;
        settings.planar = true;
        const ClearanceGrid grid(mesh, nullptr, {}, settings);
        EXPECT_EQ(grid.cells()[2], 1);
        const TriangleMesh shadow = shadowOf(mesh);
        std::uniform_real_distribution<double> w(-1.6, 1.6);
        constexpr int kPoints = 3000;
        int positiveSeen = 0;
        for (int i = 0; i < kPoints; ++i)
        {
            const Vec3 p = scale * Vec3(w(rng), w(rng), 0.0);
            const ClearanceSample s = grid.at(p);
            ASSERT_LE(s.clearance, pointMeshDistance(shadow, p)) << "scale " << scale << " point " << p.transpose();
            ASSERT_FALSE(s.inside);  // no sides on a footprint grid
            expectClearsAgreesWithAt(grid, p, s, scale);
            positiveSeen += s.clearance > 0.0;
        }
        EXPECT_GT(positiveSeen, kPoints / 10) << "scale " << scale;
    }
}

// The footprint grid's occupied cells (those that keep a triangle): every cell a shadow touches,
// found by sampling each shadow densely (corners, edges, inside), and no cell whose centre lies
// beyond the occupancy reach (half a cube's diagonal) of every shadow, by an independent distance.
// Shadows of every kind: flat triangles, upright faces (segments, slanted or along the axes),
// slivers, and a vertical edge-on face whose shadow is a point.
TEST(ClearanceGrid, FootprintOccupiesTheCellsItsShadowsTouchAndNoFarOnes)
{
    test::TestRandom rng(test::seeded(19));
    for (double scale : {1e-6, 1.0, 1e6})
    {
        TriangleMesh mesh = clutterWithUprightFaces(rng, scale);
        append(mesh, uprightTriangle(scale * Vec3(-0.9, 0.25, 0), scale * Vec3(0.9, 0.25, 0), 0.0, scale));
        append(mesh, uprightTriangle(scale * Vec3(0.4, -0.9, 0), scale * Vec3(0.4, 0.9, 0), 0.0, scale));
        TriangleMesh odd;
        odd.vertices = {scale * Vec3(-0.8, -0.5, 0.1), scale * Vec3(0.8, -0.5 + 1e-7, 0.1),
                        scale * Vec3(0.0, -0.5, 0.2),  // a sliver with an edge almost along x
                        scale * Vec3(0.1, 0.6, 0.0),   scale * Vec3(0.1, 0.6, 0.5),
                        scale * Vec3(0.1, 0.6, 1.0)};  // upright and edge on: its shadow is a point
        odd.triangles = {{0, 1, 2}, {3, 4, 5}};
        append(mesh, odd);
        ClearanceGridSettings settings;
        settings.maxCells = 1 << 13;
        settings.margin = 0.3 * scale;
        settings.planar = true;
        settings.keepTriangles = true;
        const ClearanceGrid grid(mesh, nullptr, {}, settings);
        const TriangleMesh shadow = shadowOf(mesh);
        constexpr int kSteps = 24;
        for (std::size_t t = 0; t < shadow.triangleCount(); ++t)
            for (int i = 0; i <= kSteps; ++i)
                for (int j = 0; i + j <= kSteps; ++j)
                {
                    const Vec3 &a = shadow.corner(t, 0), &b = shadow.corner(t, 1), &c = shadow.corner(t, 2);
                    const Vec3 p = a + (b - a) * (double(i) / kSteps) + (c - a) * (double(j) / kSteps);
                    ASSERT_GE(grid.triangleNear(p), 0)
                        << "scale " << scale << " triangle " << t << " point " << p.transpose();
                }
        const BoundingBox box = shadow.bounds();
        const double h = grid.cellSize();
        int far = 0;
        for (int y = 0; y < grid.cells()[1]; ++y)
            for (int x = 0; x < grid.cells()[0]; ++x)
            {
                const Vec3 centre(box.min.x() - settings.margin + h * (x + 0.5),
                                  box.min.y() - settings.margin + h * (y + 0.5), 0.0);
                if (pointMeshDistance(shadow, centre) > 0.87 * h)
                {
                    ASSERT_LT(grid.triangleNear(centre), 0) << "scale " << scale << " centre " << centre.transpose();
                    ++far;
                }
            }
        EXPECT_GT(far, grid.cells()[0] * grid.cells()[1] / 10) << "scale " << scale;
    }
}

// A planar scene (CollisionScene::planarPoses): the footprint proof against bruteforce, with
// triangles above and below the robot's height (a ceiling within the height margin, a floor beyond
// it), slanted upright walls, closed boxes, a tall room the robot can sit inside and a small box the
// closed robot can swallow; planar poses, poses brought to within 1e-9 of contact, and poses that are not planar
// (tilted, or lifted off z = 0), which the 3D grid answers instead.
TEST(GridFirst, PlanarScenesAgreeWithBruteForce)
{
    test::TestRandom rng(test::seeded(18));
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (double scale : {1e-3, 1.0, 1e3})
        for (ContactSemantics semantics : {ContactSemantics::Solid, ContactSemantics::SurfaceOnly})
        {
            TriangleMesh robot = test::boxMesh(scale * Vec3(-0.12, -0.04, 0.0), scale * Vec3(0.12, 0.04, 0.3));
            append(robot, test::boxMesh(scale * Vec3(0.08, -0.1, 0.1), scale * Vec3(0.11, 0.1, 0.2)));
            const double reach = robot.radiusAboutOrigin();
            TriangleMesh env;
            for (int i = 0; i < 8; ++i)
            {
                const Vec3 c(u(rng), u(rng), 0.15);
                const Vec3 half(0.05 + 0.2 * std::abs(u(rng)), 0.05 + 0.2 * std::abs(u(rng)), 0.3);
                append(env, test::boxMesh(scale * (c - half), scale * (c + half)));
            }
            // A ceiling within the height margin (0.2 of the reach above the robot's top), a floor and
            // the top and bottom of a room beyond it (3 reaches): the floor and the room's lids are
            // left out of the footprint, so only the probes put the robot inside the room.
            const double r = reach / scale;
            append(env, test::boxMesh(scale * Vec3(0.0, -1.4, 0.3 + 0.2 * r), scale * Vec3(1.4, 0.0, 0.35 + 0.2 * r)));
            append(env, test::boxMesh(scale * Vec3(-1.5, -1.5, -3.0 * r - 0.1), scale * Vec3(1.5, 1.5, -3.0 * r)));
            append(env,
                   test::boxMesh(scale * Vec3(-1.4, 0.9, -3.0 * r - 0.05), scale * Vec3(-0.9, 1.4, 0.35 + 3.0 * r)));
            append(env, test::boxMesh(scale * Vec3(1.0, -1.0, 0.12), scale * Vec3(1.01, -0.99, 0.13)));  // a crumb
            for (int i = 0; i < 5; ++i)
                append(env, uprightTriangle(scale * Vec3(u(rng), u(rng), 0), scale * Vec3(u(rng), u(rng), 0),
                                            -0.1 * scale, 0.5 * scale));
            CollisionScene scene;
            scene.robot = shared(robot);
            scene.environment = shared(env);
            scene.planarPoses = true;
            const auto brute = makeChecker("bruteforce", scene);

            std::vector<RigidTransform> poses;
            const auto planar = [&] {
                return RigidTransform::fromPlanarPose(1.5 * scale * u(rng), 1.5 * scale * u(rng), M_PI * u(rng));
            };
            for (int i = 0; i < test::cases(300); ++i)
                poses.push_back(planar());
            for (double yaw : {0.0, 0.3, 1.2})
                poses.push_back(RigidTransform::fromPlanarPose(-1.15 * scale, 1.15 * scale, yaw));  // in the room
            poses.push_back(RigidTransform::fromPlanarPose(1.005 * scale, -0.995 * scale, 0.0));    // around the crumb
            // Near contact: bisect between a free and a colliding planar pose of one yaw.
            for (int pair = 0; pair < test::cases(40); ++pair)
            {
                RigidTransform in = planar(), out = planar();
                out.rotation = in.rotation;
                if (brute->collides(in) == brute->collides(out))
                    continue;
                if (brute->collides(out))
                    std::swap(in, out);
                for (int k = 0; k < 60 && (in.translation - out.translation).norm() > 1e-9 * scale; ++k)
                {
                    const Vec3 mid = 0.5 * (in.translation + out.translation);
                    (brute->collides({in.rotation, mid}) ? in.translation : out.translation) = mid;
                }
                poses.push_back(in);
                poses.push_back(out);
            }
            // Not planar: tilted or lifted copies of the poses so far (near contact included),
            // lifted by a hair or far enough to reach the ceiling or sink into the floor.
            const std::size_t planarCount = poses.size();
            for (std::size_t i = 0; i < planarCount; i += 3)
            {
                RigidTransform moved = poses[i];
                if (i % 2 == 0)
                    moved.rotation =
                        Eigen::AngleAxisd(1e-3 * u(rng), Vec3::UnitX()).toRotationMatrix() * moved.rotation;
                else
                    moved.translation.z() = (i % 4 == 1 ? 1e-9 * scale : 0.3 * reach) * u(rng);
                poses.push_back(moved);
            }
            const Verdicts v = expectAgreement(scene, semantics, poses);
            EXPECT_GT(v.freeProved, v.free / 3) << "scale " << scale;
            EXPECT_GT(v.colliding, test::cases(300) / 15) << "scale " << scale;  // 20 unsanitized

            // Swept proximity on planar poses: a proof with slack t and radial rate r means no robot
            // point p comes within t + r |p|: checked at every robot vertex (the exact distance
            // from it), and for the whole robot against t.
            CheckerOptions options;
            options.semantics = semantics;
            const auto checker = makeChecker("obb", scene, options);
            const auto *grid = dynamic_cast<const GridFirstChecker *>(checker.get());
            ASSERT_NE(grid, nullptr);
            const auto surfaces = makeChecker("bruteforce", scene, ContactSemantics::SurfaceOnly);
            int proved = 0;
            // A fixed count (24 robot vertices against a few hundred triangles: cheap under the
            // sanitizers too); the floor on proofs below needs it.
            for (int i = 0; i < 300; ++i)
            {
                const RigidTransform pose = planar();
                const double slack = 0.03 * scale * (i % 5), radial = 0.05 * (i % 3);
                if (!grid->freeByGrid(pose, slack, radial))
                    continue;
                ++proved;
                EXPECT_GT(surfaces->distance(pose), slack - 1e-12 * scale) << i;
                if (semantics == ContactSemantics::Solid)
                    EXPECT_FALSE(brute->collides(pose)) << i;
                for (const Vec3 &v : robot.vertices)
                    EXPECT_GT(pointMeshDistance(env, pose.apply(v)), slack + radial * v.norm() - 1e-12 * scale) << i;
            }
            EXPECT_GT(proved, 30) << "scale " << scale;
        }
}
