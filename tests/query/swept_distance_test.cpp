// SPDX-License-Identifier: BSD-3-Clause
// withinSweptDistance is what continuous motion checking rests on: "false" must prove that no robot
// point p comes within translationSlack + radialSlack * |p| of the environment. Checked here for
// every checker against exact point-to-triangle distances on points sampled densely over the robot's
// surface, and along motions against brute-force collision checks at many poses of each certified
// interval.
#include "support/test_support.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/query/checker_catalogue.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace hcd;

namespace
{
// Points on every robot triangle (robot frame): a barycentric grid with `k` + 1 points per edge.
std::vector<Vec3> surfaceSamples(const TriangleMesh &robot, int k)
{
    std::vector<Vec3> points;
    for (std::uint32_t t = 0; t < robot.triangleCount(); ++t)
        for (int i = 0; i <= k; ++i)
            for (int j = 0; i + j <= k; ++j)
            {
                const double u = double(i) / k, v = double(j) / k;
                points.push_back((1.0 - u - v) * robot.corner(t, 0) + u * robot.corner(t, 1) + v * robot.corner(t, 2));
            }
    return points;
}

// Exact distance (to rounding) from a world point to the environment's surface.
double distanceToSurface(const Vec3 &p, const TriangleMesh &environment)
{
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t t = 0; t < environment.triangleCount(); ++t)
        best = std::min(best, (p - closestPointOnTriangle(p, environment.corner(t, 0), environment.corner(t, 1),
                                                          environment.corner(t, 2)))
                                  .norm());
    return best;
}

// OMPL's SE3 interpolation: translation linear in tau, rotation along the shortest great arc.
RigidTransform interpolate(const RigidTransform &a, const RigidTransform &b, double tau)
{
    const Eigen::Quaterniond qa(a.rotation), qb(b.rotation);
    return {qa.slerp(tau, qb).toRotationMatrix(), (1.0 - tau) * a.translation + tau * b.translation};
}

double rotationAngle(const Mat3 &a, const Mat3 &b)
{
    return std::acos(std::clamp(0.5 * ((a.transpose() * b).trace() - 1.0), -1.0, 1.0));
}
}  // namespace

namespace
{
// For every checker over `scene`: where withinSweptDistance says false at a pose, no robot surface
// sample comes within its reach (translation slack up to maxSlack, radial up to maxRadial), and
// bruteforce finds no collision; both answers are common; with no slack it is the collision query.
void expectFalseProvesEveryPointBeyondItsReach(const CollisionScene &scene, const std::vector<RigidTransform> &poses,
                                               double maxSlack, double maxRadial, std::uint64_t seed)
{
    const TriangleMesh &robot = *scene.robot, &environment = *scene.environment;
    const double radius = robot.radiusAboutOrigin();
    const std::vector<Vec3> samples = surfaceSamples(robot, 4);
    test::TestRandom rng(test::seeded(seed));
    std::uniform_real_distribution<double> slack(0.0, maxSlack), radial(0.0, maxRadial);
    const auto reference = makeChecker("bruteforce", scene);
    for (const std::string &name : CheckerCatalogue::builtIn().names())
    {
        const auto checker = makeChecker(name, scene);
        std::size_t proven = 0, notProven = 0;
        for (const RigidTransform &pose : poses)
        {
            const double t = slack(rng), r = radial(rng);
            if (checker->withinSweptDistance(pose, t, r, radius))
            {
                ++notProven;
                continue;
            }
            ++proven;
            ASSERT_FALSE(reference->collides(pose)) << name;
            for (const Vec3 &p : samples)
                ASSERT_GT(distanceToSurface(pose.apply(p), environment), t + r * p.norm())
                    << name << ": robot point (" << p.transpose() << ") is within its reach";
        }
        // Both answers common on these poses, or the test proves little.
        EXPECT_GT(proven, 20u) << name;
        EXPECT_GT(notProven, 20u) << name;
        // With no slack the query is the collision query.
        for (std::size_t i = 0; i < 40; ++i)
            EXPECT_EQ(checker->withinSweptDistance(poses[i], 0.0, 0.0, radius), reference->collides(poses[i])) << name;
    }
}
}  // namespace

TEST(SweptDistance, FalseProvesEveryRobotPointIsBeyondItsReach)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    test::TestRandom rng(test::seeded(31));
    const auto poses = test::randomPoses(problem, 240, rng);
    expectFalseProvesEveryPointBeyondItsReach(problem.scene, poses, 0.5, 0.03, 31);
}

TEST(SweptDistance, FalseProvesEveryPointBeyondItsReachForARobotLargerThanItsEnvironment)
{
    // The window as the robot and the small block as the environment: the traversal splits the
    // robot's nodes from the root down, so the robot's boxes are tested four at a time with the
    // largest reach among them.
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    CollisionScene swapped = problem.scene;
    std::swap(swapped.robot, swapped.environment);
    ASSERT_GT(swapped.robot->triangleCount(), 2 * swapped.environment->triangleCount());
    test::TestRandom rng(test::seeded(37));
    // The window turned about its own origin within a third of its size of the block.
    std::vector<RigidTransform> poses;
    std::uniform_real_distribution<double> offset(-20.0, 20.0);
    for (int i = 0; i < 240; ++i)
        poses.push_back({test::randomRotation(rng), Vec3(offset(rng), offset(rng), offset(rng))});
    expectFalseProvesEveryPointBeyondItsReach(swapped, poses, 0.5, 0.03, 37);
}

TEST(SweptDistance, CertifiedMotionIntervalsAreFreeUnderDenseSampling)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    const double radius = problem.robot.mesh->radiusAboutOrigin();
    test::TestRandom rng(test::seeded(32));
    // Twice the intervals each check below needs, so that both counts clear them whatever the seed.
    const auto starts = test::randomPoses(problem, 240, rng);
    std::uniform_real_distribution<double> step(-4.0, 4.0), unit(0.0, 1.0);
    const auto reference = makeChecker("bruteforce", problem.scene);
    for (const std::string &name : {"obb", "hybrid", "ellipsoid", "lp", "bruteforce"})
    {
        const auto checker = makeChecker(name, problem.scene);
        std::size_t certified = 0, refused = 0;
        test::TestRandom motionRng(test::seeded(33));
        for (const RigidTransform &a : starts)
        {
            // A motion of a few units with a random turn, and a random interval [lo, hi] of it.
            const RigidTransform turn = RigidTransform::fromAxisAngle(
                Vec3::Zero(), Vec3(step(motionRng), step(motionRng), step(motionRng)), 0.8 * unit(motionRng));
            const RigidTransform b{turn.rotation * a.rotation,
                                   a.translation + Vec3(step(motionRng), step(motionRng), step(motionRng))};
            const double lo = 0.5 * unit(motionRng), hi = lo + 0.5 * unit(motionRng);
            const double half = 0.5 * (hi - lo);
            const double translationSlack = (b.translation - a.translation).norm() * half * (1.0 + 1e-9);
            const double radialSlack = rotationAngle(a.rotation, b.rotation) * half * (1.0 + 1e-9) + 1e-15;
            if (checker->withinSweptDistance(interpolate(a, b, lo + half), translationSlack, radialSlack, radius))
            {
                ++refused;
                continue;
            }
            ++certified;
            for (int k = 0; k <= 200; ++k)
                ASSERT_FALSE(reference->collides(interpolate(a, b, lo + (hi - lo) * k / 200)))
                    << name << ": a certified interval collides at sample " << k;
        }
        EXPECT_GT(certified, 15u) << name;
        EXPECT_GT(refused, 15u) << name;
    }
}

TEST(SweptDistance, NearPairListsHoldEveryPairWithinItsReach)
{
    // window_3d has no repeated faces, so the checkers' own triangle indices are the meshes'.
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    const TriangleMesh &robot = *problem.robot.mesh, &environment = *problem.world.mesh;
    ASSERT_EQ(withoutRepeatedFaces(problem.robot.mesh).dropped, 0u);
    ASSERT_EQ(withoutRepeatedFaces(problem.world.mesh).dropped, 0u);
    std::vector<double> reach(robot.triangleCount());
    for (std::uint32_t t = 0; t < robot.triangleCount(); ++t)
        reach[t] = std::max({robot.corner(t, 0).norm(), robot.corner(t, 1).norm(), robot.corner(t, 2).norm()});
    test::TestRandom rng(test::seeded(34));
    const auto poses = test::randomPoses(problem, test::cases(160), rng);
    std::uniform_real_distribution<double> slack(0.0, 2.0), radial(0.0, 0.05), unit(0.0, 1.0);
    for (const std::string &name : {"auto", "obb", "aabb", "kdop18", "ellipsoid", "hybrid"})
    {
        const auto checker = makeChecker(name, problem.scene);
        QueryContext context;
        std::size_t listed = 0, pairsSeen = 0, narrowed = 0;
        for (const RigidTransform &pose : poses)
        {
            const double t = slack(rng) + 1e-3, r = radial(rng);
            std::vector<TrianglePair> near;
            if (!checker->listSweptNearPairs(pose, t, r, 1u << 20, near, context))
                continue;
            ++listed;
            pairsSeen += near.size();
            const auto isListed = [&](std::uint32_t i, std::uint32_t j) {
                return std::any_of(near.begin(), near.end(),
                                   [&](const TrianglePair &p) { return p.robot == i && p.environment == j; });
            };
            // Brute force: every pair within its reach (with room for rounding) is listed.
            for (std::uint32_t i = 0; i < robot.triangleCount(); ++i)
            {
                const Vec3 a0 = pose.apply(robot.corner(i, 0)), a1 = pose.apply(robot.corner(i, 1)),
                           a2 = pose.apply(robot.corner(i, 2));
                for (std::uint32_t j = 0; j < environment.triangleCount(); ++j)
                    if (triangleDistance(a0, a1, a2, environment.corner(j, 0), environment.corner(j, 1),
                                         environment.corner(j, 2)) <= 0.999 * (t + r * reach[i]))
                        ASSERT_TRUE(isListed(i, j))
                            << name << ": pair " << i << ", " << j << " within reach, not listed";
            }
            // Among the listed pairs, at a smaller slack: the same brute force, and contact exactly
            // when a listed pair intersects.
            const double t2 = t * unit(rng), r2 = r * unit(rng);
            std::vector<TrianglePair> nearer;
            const bool touching = checker->sweptNearPairsAmong(pose, t2, r2, near, nearer, context);
            narrowed += nearer.size() < near.size();
            bool intersecting = false;
            for (const TrianglePair &p : near)
            {
                const Vec3 a0 = pose.apply(robot.corner(p.robot, 0)), a1 = pose.apply(robot.corner(p.robot, 1)),
                           a2 = pose.apply(robot.corner(p.robot, 2));
                const Vec3 &b0 = environment.corner(p.environment, 0), &b1 = environment.corner(p.environment, 1),
                           &b2 = environment.corner(p.environment, 2);
                intersecting = intersecting || trianglesIntersect(a0, a1, a2, b0, b1, b2);
                if (triangleDistance(a0, a1, a2, b0, b1, b2) <= 0.999 * (t2 + r2 * reach[p.robot]))
                    ASSERT_TRUE(std::any_of(nearer.begin(), nearer.end(), [&](const TrianglePair &q) {
                        return q.robot == p.robot && q.environment == p.environment;
                    })) << name;
            }
            ASSERT_EQ(touching, intersecting) << name;
        }
        // Not vacuous: tree checkers list, and lists get narrower at smaller slacks.
        EXPECT_GT(listed, poses.size() / 2) << name;
        EXPECT_GT(pairsSeen, listed) << name;
        EXPECT_GT(narrowed, listed / 4) << name;
    }
    // A checker that cannot list says so.
    std::vector<TrianglePair> near;
    QueryContext context;
    EXPECT_FALSE(
        makeChecker("bruteforce", problem.scene)->listSweptNearPairs(poses.front(), 1.0, 0.0, 1u << 20, near, context));
}

TEST(SweptDistance, IntervalsCertifiedByTheirNearPairsAreFreeUnderDenseSampling)
{
    // A front listed on an interval, then tested alone on a part of it, as the motion validator does.
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    test::TestRandom rng(test::seeded(35));
    const auto starts = test::randomPoses(problem, test::cases(400), rng);
    std::uniform_real_distribution<double> step(-4.0, 4.0), unit(0.0, 1.0);
    const auto reference = makeChecker("bruteforce", problem.scene);
    const auto checker = makeChecker("auto", problem.scene);
    QueryContext context;
    std::size_t certifiedByPairs = 0, touchingSeen = 0;
    for (const RigidTransform &a : starts)
    {
        const RigidTransform turn =
            RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3(step(rng), step(rng), step(rng)), 0.8 * unit(rng));
        const RigidTransform b{turn.rotation * a.rotation, a.translation + Vec3(step(rng), step(rng), step(rng))};
        const double translationRate = (b.translation - a.translation).norm() * (1.0 + 1e-9);
        const double angleRate = rotationAngle(a.rotation, b.rotation) * (1.0 + 1e-9) + 1e-15;
        // An interval [lo, hi] whose front is listed, and a part [lo2, hi2] of it (drawn first, so
        // that the cases drawn do not depend on the checker's answers).
        const double lo = 0.5 * unit(rng), hi = lo + 0.5 * unit(rng), half = 0.5 * (hi - lo);
        const double lo2 = lo + (hi - lo) * 0.5 * unit(rng), hi2 = lo2 + (hi - lo2) * unit(rng);
        std::vector<TrianglePair> front, near;
        if (!checker->listSweptNearPairs(interpolate(a, b, lo + half), translationRate * half, angleRate * half, 4096,
                                         front, context))
            continue;
        const double half2 = 0.5 * (hi2 - lo2);
        const RigidTransform middle = interpolate(a, b, lo2 + half2);
        if (checker->sweptNearPairsAmong(middle, translationRate * half2, angleRate * half2, front, near, context))
        {
            ++touchingSeen;
            ASSERT_TRUE(reference->collides(middle)) << "a touching pair at a free state";
            continue;
        }
        // Surfaces apart over [lo2, hi2]: free throughout when free at its start (no containment
        // begins without the surfaces meeting).
        if (!near.empty() || reference->collides(interpolate(a, b, lo2)))
            continue;
        ++certifiedByPairs;
        for (int k = 0; k <= 200; ++k)
            ASSERT_FALSE(reference->collides(interpolate(a, b, lo2 + (hi2 - lo2) * k / 200)))
                << "an interval certified by its near pairs collides at sample " << k;
    }
    // Not vacuous: about one start in ten certifies an interval by its pairs (fewer starts in
    // sanitizer builds).
    EXPECT_GT(certifiedByPairs, starts.size() / 40);
    EXPECT_GT(touchingSeen, 0u);
}

TEST(SweptDistance, NearPairListsRefuseWhatPairsCannotDecide)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    test::TestRandom rng(test::seeded(36));
    const auto poses = test::randomPoses(problem, 60, rng);
    QueryContext context;
    std::vector<TrianglePair> near;
    // The limit: a list of n pairs needs a limit of at least n.
    const auto obb = makeChecker("obb", problem.scene);
    std::size_t limitsTried = 0;
    for (const RigidTransform &pose : poses)
    {
        if (!obb->listSweptNearPairs(pose, 1.5, 0.02, 1u << 20, near, context) || near.size() < 2)
            continue;
        const std::size_t n = near.size();
        EXPECT_TRUE(obb->listSweptNearPairs(pose, 1.5, 0.02, n, near, context));
        EXPECT_EQ(near.size(), n);
        EXPECT_FALSE(obb->listSweptNearPairs(pose, 1.5, 0.02, n - 1, near, context));
        ++limitsTried;
    }
    EXPECT_GT(limitsTried, 5u);
    // Zero, negative or non-finite slacks, and non-finite poses, are refused; a filter at a
    // non-finite pose keeps every pair and counts as a collision.
    EXPECT_FALSE(obb->listSweptNearPairs(poses[0], 0.0, 0.0, 64, near, context));
    EXPECT_FALSE(obb->listSweptNearPairs(poses[0], -1.0, 0.5, 64, near, context));
    EXPECT_FALSE(obb->listSweptNearPairs(poses[0], std::numeric_limits<double>::quiet_NaN(), 0.0, 64, near, context));
    RigidTransform broken = poses[0];
    broken.translation.x() = std::numeric_limits<double>::infinity();
    EXPECT_FALSE(obb->listSweptNearPairs(broken, 1.0, 0.0, 64, near, context));
    const std::vector<TrianglePair> some{{0, 0}, {1, 2}};
    EXPECT_TRUE(obb->sweptNearPairsAmong(broken, 1.0, 0.0, some, near, context));
    EXPECT_EQ(near.size(), some.size());
    // Leaves decided by convex pieces or approximate spheres: no pair lists.
    CheckerOptions approximate;
    approximate.approximateTolerance = 0.01;
    for (const auto &checker : {makeChecker("lp", problem.scene), makeChecker("lp", problem.scene, approximate),
                                makeChecker("medial", problem.scene, approximate)})
        for (const RigidTransform &pose : poses)
            ASSERT_FALSE(checker->listSweptNearPairs(pose, 1.5, 0.02, 1u << 20, near, context)) << checker->name();
    // A robot inside a closed obstacle, far from its surfaces: no list with solids (that pose
    // collides), an empty one for surfaces alone.
    CollisionScene scene;
    scene.environment = std::make_shared<const TriangleMesh>(test::boxMesh(Vec3(-10, -10, -10), Vec3(10, 10, 10)));
    scene.robot = std::make_shared<const TriangleMesh>(test::boxMesh(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
    const RigidTransform inside{Mat3::Identity(), Vec3(1, 2, 3)};
    for (const std::string &name : {"auto", "obb", "kdop18"})
    {
        EXPECT_FALSE(makeChecker(name, scene)->listSweptNearPairs(inside, 0.5, 0.01, 64, near, context)) << name;
        EXPECT_TRUE(makeChecker(name, scene, ContactSemantics::SurfaceOnly)
                        ->listSweptNearPairs(inside, 0.5, 0.01, 64, near, context))
            << name;
        EXPECT_TRUE(near.empty()) << name;
    }
}

namespace
{
// corridor_2d with its robot stretched 6x along z: most of the robot's reach about its origin is
// then height, which a turn about the z axis does not move.
CollisionScene tallRobotScene(const LoadedProblem &problem, bool turnsAboutRobotZ)
{
    auto tall = std::make_shared<TriangleMesh>(*problem.robot.mesh);
    for (Vec3 &v : tall->vertices)
        v.z() *= 6.0;
    CollisionScene scene = problem.scene;
    scene.robot = tall;
    scene.planarPoses = true;
    scene.turnsAboutRobotZ = turnsAboutRobotZ;
    return scene;
}
}  // namespace

TEST(SweptDistance, TurnsAboutTheRobotZAxisCountRadialSlackFromIt)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/corridor_2d.cfg"));
    const CollisionScene scene = tallRobotScene(problem, true), anyAxis = tallRobotScene(problem, false);
    const TriangleMesh &robot = *scene.robot, &environment = *scene.environment;
    ASSERT_GT(robot.radiusAboutOrigin(), 1.5 * robot.radiusAboutZAxis());
    const std::vector<Vec3> samples = surfaceSamples(robot, 4);
    test::TestRandom rng(test::seeded(37));
    const auto poses = test::randomPoses(problem, 480, rng);  // planar: (x, y, yaw)
    std::uniform_real_distribution<double> slack(0.0, 0.1), radial(0.0, 1.5);
    const auto reference = makeChecker("bruteforce", scene);
    for (const std::string &name : CheckerCatalogue::builtIn().names())
    {
        const auto checker = makeChecker(name, scene), fromOrigin = makeChecker(name, anyAxis);
        // bruteforce has no reaches of its own: it takes the robot radius it is given for every
        // point, so it counts from wherever its caller does and says it counts from the origin.
        EXPECT_EQ(checker->turnsAboutRobotZ(), name != "bruteforce") << name;
        EXPECT_FALSE(fromOrigin->turnsAboutRobotZ()) << name;
        std::size_t proven = 0, notProven = 0, gained = 0;
        test::TestRandom slackRng(test::seeded(38));
        for (const RigidTransform &pose : poses)
        {
            const double t = slack(slackRng), r = radial(slackRng);
            const bool firstLayer = checker->sweptFreeByFirstLayer(pose, t, r);
            const bool within = checker->withinSweptDistance(pose, t, r, robot.radiusAboutZAxis());
            // A first layer's proof is one the full query makes too.
            ASSERT_FALSE(firstLayer && within) << name;
            if (within)
            {
                ++notProven;
                continue;
            }
            ++proven;
            // The same robot radius for both: only the checker's own reaches differ.
            gained += fromOrigin->withinSweptDistance(pose, t, r, robot.radiusAboutZAxis());
            ASSERT_FALSE(reference->collides(pose)) << name;
            for (const Vec3 &p : samples)
                ASSERT_GT(distanceToSurface(pose.apply(p), environment), t + r * p.head<2>().norm())
                    << name << ": robot point (" << p.transpose() << ") is within its reach about the z axis";
        }
        EXPECT_GT(proven, 20u) << name;
        EXPECT_GT(notProven, 20u) << name;
        // Counting from the axis proves poses that counting from the origin cannot.
        if (name != "bruteforce")
            EXPECT_GT(gained, 0u) << name << " of " << proven;
    }
}

TEST(SweptDistance, CertifiedTurnsAboutTheRobotZAxisAreFreeUnderDenseSampling)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/corridor_2d.cfg"));
    const CollisionScene scene = tallRobotScene(problem, true);
    const double radius = scene.robot->radiusAboutZAxis();
    test::TestRandom rng(test::seeded(39));
    const auto starts = test::randomPoses(problem, 240, rng);
    std::uniform_real_distribution<double> step(-3.0, 3.0), unit(0.0, 1.0);
    const auto reference = makeChecker("bruteforce", scene);
    for (const std::string &name : {"auto", "obb", "aabb", "kdop18", "octree", "bruteforce"})
    {
        const auto checker = makeChecker(name, scene);
        std::size_t certified = 0, refused = 0;
        test::TestRandom motionRng(test::seeded(40));
        for (const RigidTransform &a : starts)
        {
            // SE(2): x, y and yaw linear in tau (a turn of up to 2 rad), and an interval [lo, hi].
            const double yawA = std::atan2(a.rotation(1, 0), a.rotation(0, 0));
            const double dx = step(motionRng), dy = step(motionRng), turn = 2.0 * (unit(motionRng) - 0.5) * 2.0;
            const auto at = [&](double tau) {
                return RigidTransform::fromPlanarPose(a.translation.x() + tau * dx, a.translation.y() + tau * dy,
                                                      yawA + tau * turn);
            };
            const double lo = 0.5 * unit(motionRng), hi = lo + 0.5 * unit(motionRng);
            const double half = 0.5 * (hi - lo);
            const double translationSlack = std::hypot(dx, dy) * half * (1.0 + 1e-9);
            const double radialSlack = std::abs(turn) * half * (1.0 + 1e-9) + 1e-15;
            if (checker->withinSweptDistance(at(lo + half), translationSlack, radialSlack, radius))
            {
                ++refused;
                continue;
            }
            ++certified;
            for (int k = 0; k <= 200; ++k)
                ASSERT_FALSE(reference->collides(at(lo + (hi - lo) * k / 200)))
                    << name << ": a certified interval collides at sample " << k;
        }
        EXPECT_GT(certified, 15u) << name;
        EXPECT_GT(refused, 15u) << name;
    }
}
