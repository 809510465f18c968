// SPDX-License-Identifier: BSD-3-Clause
// Scenes of many bodies: the broad phase and the narrow phases against the brute-force scene, the
// continuous motion check against dense sampling, allowed pairs and self-pairs, and the .cfg
// format of scene problems (every error names its file and line).
#include "support/test_support.h"

#include "hybridcd/io/input_error.h"
#include "hybridcd/io/problem_scene.h"
#include "hybridcd/scene/problem_bodies.h"
#include "hybridcd/scene/scene.h"
#include "hybridcd/scene/scene_motion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace hcd
{
namespace
{
using test::TestRandom;

const double kPi = std::acos(-1.0);

// Robot poses uniform over a box of positions (and yaw only for planar scenes).
std::vector<RigidTransform> randomState(std::size_t robots, const Vec3 &lo, const Vec3 &hi, bool planar,
                                        TestRandom &rng)
{
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<RigidTransform> poses(robots);
    for (RigidTransform &pose : poses)
    {
        const Vec3 t = lo + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(hi - lo);
        pose = planar ? RigidTransform::fromPlanarPose(t.x(), t.y(), (2.0 * unit(rng) - 1.0) * kPi)
                      : RigidTransform{test::randomRotation(rng), t};
    }
    return poses;
}

LoadedProblem crossing() { return loadProblem(test::sourcePath("problems/crossing_2d.cfg")); }

// A 3D scene: two mesh robots and two primitive robots among every primitive kind and a mesh.
std::shared_ptr<const Scene> clutter(const SceneOptions &options)
{
    auto boxMesh = std::make_shared<const TriangleMesh>(test::boxMesh(Vec3(-1.0, -0.3, -0.5), Vec3(1.0, 0.3, 0.5)));
    auto wall = std::make_shared<const TriangleMesh>(test::boxMesh(Vec3(-0.1, -4.0, -4.0), Vec3(0.1, 4.0, 4.0)));
    std::vector<SceneBody> bodies;
    auto body = [&](std::string label, Shape shape, int robot, RigidTransform pose = RigidTransform()) {
        bodies.push_back({std::move(label), std::make_shared<const BodyGeometry>(std::move(shape)), robot, pose});
    };
    body("robot", Shape::mesh(boxMesh), 0);
    body("robot.2", Shape::mesh(boxMesh), 1);
    body("robot.3", Shape::capsule(0.4, 0.6), 2);
    body("robot.4", Shape::box(Vec3(0.5, 0.2, 0.7)), 3);
    body("world", Shape::mesh(wall), -1);
    body("obstacle.1", Shape::sphere(1.0), -1, RigidTransform{Mat3::Identity(), Vec3(2.5, 2.0, 0.0)});
    body("obstacle.2", Shape::cylinder(0.5, 1.5), -1, RigidTransform{Mat3::Identity(), Vec3(-2.5, -2.0, 1.0)});
    body("obstacle.3", Shape::cone(0.8, 1.0), -1, RigidTransform{Mat3::Identity(), Vec3(-2.0, 2.5, -1.0)});
    body("obstacle.4", Shape::ellipsoid(Vec3(1.2, 0.4, 0.6)), -1,
         RigidTransform::fromAxisAngle(Vec3(2.0, -2.5, 0.5), Vec3(1.0, 1.0, 0.0), 0.7));
    body("obstacle.5", Shape::halfspace(Vec3(0.0, 0.0, 1.0), -5.5), -1);
    body("obstacle.6", Shape::convex({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}), -1,
         RigidTransform{Mat3::Identity(), Vec3(0.5, 3.0, 2.0)});
    return std::make_shared<const Scene>(std::move(bodies), 4, std::vector<std::pair<std::size_t, std::size_t>>{},
                                         options);
}

TEST(Scene, BroadPhaseAndNarrowPhasesAgreeWithBruteForceInClutter)
{
    SceneOptions reference;
    reference.bruteForce = true;
    const auto fast = clutter({}), slow = clutter(reference);
    ASSERT_EQ(fast->pairs().size(), slow->pairs().size());
    // 4 robots: 4 x 7 statics + 6 robot pairs.
    EXPECT_EQ(fast->pairs().size(), 4u * 7u + 6u);
    TestRandom rng(test::seeded(71));
    QueryContext fastContext, slowContext;
    int colliding = 0;
    const int n = test::cases(600);
    for (int i = 0; i < n; ++i)
    {
        const auto poses = randomState(4, Vec3(-6, -6, -6), Vec3(6, 6, 6), false, rng);
        const bool hit = slow->collides(poses, slowContext);
        ASSERT_EQ(fast->collides(poses, fastContext), hit) << "state " << i;
        colliding += hit ? 1 : 0;
        // Every pair alone, too: the broad phase may only drop pairs that are apart.
        if (i % 10 == 0)
            for (std::size_t pair = 0; pair < fast->pairs().size(); ++pair)
                ASSERT_EQ(fast->pairCollides(pair, poses.data(), fastContext),
                          slow->pairCollides(pair, poses.data(), slowContext))
                    << fast->pairLabel(pair) << ", state " << i;
    }
    // The generator must give both answers often.
    EXPECT_GT(colliding, n / 5);
    EXPECT_LT(colliding, 4 * n / 5);
}

TEST(Scene, CoherentStreamsKeepTheBroadPhaseExact)
{
    // Small steps (as a planner's neighbouring states and a motion's), where the sweep and prune
    // moves few endpoints, and jumps between them.
    SceneOptions reference;
    reference.bruteForce = true;
    const auto fast = clutter({}), slow = clutter(reference);
    TestRandom rng(test::seeded(72));
    std::normal_distribution<double> step(0.0, 0.05);
    QueryContext fastContext, slowContext;
    auto poses = randomState(4, Vec3(-6, -6, -6), Vec3(6, 6, 6), false, rng);
    int colliding = 0;
    const int n = test::cases(2000);
    // Ten walks whatever the case count (sanitizer builds draw fewer): with only a couple of
    // starting states, both could collide (or neither) and the walk's answers would hardly vary.
    const int walk = std::max(1, n / 10);
    for (int i = 0; i < n; ++i)
    {
        if (i % walk == 0)
            poses = randomState(4, Vec3(-6, -6, -6), Vec3(6, 6, 6), false, rng);
        for (RigidTransform &pose : poses)
        {
            pose.translation += Vec3(step(rng), step(rng), step(rng));
            pose.rotation =
                (RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3(step(rng), step(rng), step(rng)), 0.05).rotation *
                 pose.rotation)
                    .eval();
        }
        const bool hit = slow->collides(poses, slowContext);
        ASSERT_EQ(fast->collides(poses, fastContext), hit) << "step " << i;
        colliding += hit ? 1 : 0;
    }
    EXPECT_GT(colliding, n / 10);
    EXPECT_LT(colliding, 9 * n / 10);
}

TEST(Scene, ProblemSceneAgreesWithBruteForce)
{
    const LoadedProblem problem = crossing();
    ASSERT_EQ(problem.config.robotCount(), 3u);
    ASSERT_EQ(problem.config.obstacles.size(), 12u);
    SceneOptions reference;
    reference.bruteForce = true;
    const auto fast = makeProblemScene(problem), slow = makeProblemScene(problem, reference);
    // 3 robots against 12 obstacles, and 3 robot pairs.
    EXPECT_EQ(fast->pairs().size(), 3u * 12u + 3u);
    TestRandom rng(test::seeded(73));
    QueryContext fastContext, slowContext;
    int colliding = 0;
    const int n = test::cases(1000);
    for (int i = 0; i < n; ++i)
    {
        const auto poses = randomState(3, Vec3(-18.5, -11.5, 0), Vec3(18.5, 11.5, 0), true, rng);
        const bool hit = slow->collides(poses, slowContext);
        ASSERT_EQ(fast->collides(poses, fastContext), hit) << "state " << i;
        colliding += hit ? 1 : 0;
    }
    EXPECT_GT(colliding, n / 5);
    EXPECT_LT(colliding, 4 * n / 5);
    // The start and goal of the problem are free.
    EXPECT_FALSE(fast->collides(problemStart(problem.config), fastContext));
    EXPECT_FALSE(fast->collides(problemGoal(problem.config), fastContext));
}

TEST(Scene, DistanceIsZeroExactlyWhenColliding)
{
    const auto scene = clutter({});
    TestRandom rng(test::seeded(74));
    QueryContext context;
    const int n = test::cases(300);
    for (int i = 0; i < n; ++i)
    {
        const auto poses = randomState(4, Vec3(-4, -4, -4), Vec3(4, 4, 4), false, rng);
        const double d = scene->distance(poses.data(), context);
        ASSERT_EQ(d == 0.0, scene->collides(poses, context)) << "state " << i << ", distance " << d;
        // The smallest pair distance, by every pair.
        double smallest = std::numeric_limits<double>::infinity();
        for (std::size_t pair = 0; pair < scene->pairs().size(); ++pair)
            smallest = std::min(smallest, scene->pairDistance(pair, poses.data(), context));
        // Up to rounding: GJK's warm start depends on the context's earlier queries.
        ASSERT_NEAR(d, smallest, 1e-9 * (1.0 + smallest));
    }
}

TEST(SceneMotion, NeverAcceptsAMotionThatDenseSamplingFindsColliding)
{
    const auto scene = clutter({});
    TestRandom rng(test::seeded(75));
    std::normal_distribution<double> offset(0.0, 1.0);
    QueryContext context;
    int rejected = 0, sampledColliding = 0;
    const int n = test::cases(150);
    for (int i = 0; i < n; ++i)
    {
        auto start = randomState(4, Vec3(-3.5, -3.5, -3), Vec3(3.5, 3.5, 3), false, rng);
        if (scene->collides(start, context))
        {
            --i;
            continue;
        }
        std::vector<RigidTransform> goal = start;
        for (RigidTransform &pose : goal)
        {
            pose.translation += 1.5 * Vec3(offset(rng), offset(rng), offset(rng));
            pose.rotation = (RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3(offset(rng), offset(rng), offset(rng)),
                                                           0.8 * offset(rng))
                                 .rotation *
                             pose.rotation)
                                .eval();
        }
        const SceneMotionResult exact = checkSceneMotion(*scene, start, goal, context);
        const SceneMotionResult sampled = checkSceneMotionBySampling(*scene, start, goal, 400, context);
        rejected += exact.valid ? 0 : 1;
        sampledColliding += sampled.valid ? 0 : 1;
        if (!sampled.valid)
        {
            ASSERT_FALSE(exact.valid) << "motion " << i << " touches at t = " << sampled.contactTime;
            // Everything before the last valid time is free, so it cannot come after a sample that collides.
            ASSERT_LE(exact.lastValidTime, sampled.contactTime + 1e-12) << "motion " << i;
        }
        if (!exact.valid)
        {
            // Everything before lastValidTime is free: spot-check it densely.
            std::vector<RigidTransform> poses;
            for (int k = 0; k <= 50; ++k)
            {
                interpolateScenePoses(start, goal, exact.lastValidTime * k / 50.0, poses);
                ASSERT_FALSE(scene->collides(poses, context)) << "motion " << i << ", before lastValid";
            }
            // At the reported contact the pair is within the tolerance of touching (1e-9 of the
            // scene), up to the accuracy of the distance recomputed here.
            interpolateScenePoses(start, goal, exact.contactTime, poses);
            ASSERT_LE(scene->pairDistance(exact.pair, poses.data(), context), 1e-7 * scene->scale()) << "motion " << i;
        }
    }
    EXPECT_GT(sampledColliding, n / 5);
    EXPECT_LT(rejected, n);
}

// A turn of half a circle goes one way or the other by the sign of a difference near zero, decided
// by rounding (OMPL's SO2 by the yaw difference, a slerp by a dot product): an arm with a post on
// one side of its sweep must be refused whichever way it is asked to turn, however rounding falls,
// while a turn short of half a circle away from the post is certified.
TEST(SceneMotion, HalfTurnsAreCertifiedBothWaysRound)
{
    std::vector<SceneBody> bodies;
    bodies.push_back({"robot", std::make_shared<const BodyGeometry>(Shape::box(Vec3(0.5, 0.05, 0.5))), 0,
                      RigidTransform{Mat3::Identity(), Vec3(0.5, 0.0, 0.0)}});
    // The post stands where the arm points half way round the clockwise turn from yaw 1.
    bodies.push_back(
        {"obstacle.1", std::make_shared<const BodyGeometry>(Shape::sphere(0.1)), -1,
         RigidTransform{Mat3::Identity(), 0.8 * Vec3(std::cos(1.0 - kPi / 2), std::sin(1.0 - kPi / 2), 0)}});
    const Scene scene(std::move(bodies), 1, {});
    QueryContext context;
    const auto sweepCollides = [&](double from, double turn) {
        for (int k = 0; k <= 400; ++k)
            if (scene.collides({RigidTransform::fromPlanarPose(0.0, 0.0, from + turn * k / 400.0)}, context))
                return true;
        return false;
    };
    for (int i = 0; i < 40; ++i)
    {
        const double from = 1.0 + 1e-3 * i;
        SCOPED_TRACE(from);
        // Clockwise meets the post, counterclockwise does not.
        ASSERT_TRUE(sweepCollides(from, -kPi));
        ASSERT_FALSE(sweepCollides(from, kPi));
        const std::vector<RigidTransform> start{RigidTransform::fromPlanarPose(0.0, 0.0, from)};
        for (const double to : {from - kPi, from + kPi, std::nextafter(from - kPi, 0.0), from + kPi * (1.0 - 1e-12)})
        {
            const std::vector<RigidTransform> goal{RigidTransform::fromPlanarPose(0.0, 0.0, to)};
            EXPECT_FALSE(checkSceneMotion(scene, start, goal, context).valid) << "to " << to;
        }
        const std::vector<RigidTransform> shortOfHalf{RigidTransform::fromPlanarPose(0.0, 0.0, from + 0.9 * kPi)};
        EXPECT_TRUE(checkSceneMotion(scene, start, shortOfHalf, context).valid);
    }
}

// A 2-long needle turning by 2e-8 rad sweeps its tip 2e-8 up, across a speck that lies between the
// states the check rakes: the turn must count whole (acos of a dot product rounds it to zero).
TEST(SceneMotion, TinyTurnsCountTheirWholeAngle)
{
    std::vector<SceneBody> bodies;
    bodies.push_back(
        {"robot", std::make_shared<const BodyGeometry>(Shape::box(Vec3(1.0, 1e-10, 0.5))), 0, RigidTransform()});
    bodies.push_back({"obstacle.1", std::make_shared<const BodyGeometry>(Shape::box(Vec3(0.005, 0.8e-9, 0.5))), -1,
                      RigidTransform{Mat3::Identity(), Vec3(0.985, 3.6e-9, 0.0)}});
    const Scene scene(std::move(bodies), 1, {});
    QueryContext context;
    for (const bool planar : {true, false})
        for (const double turn : {2e-8, 5e-8, -2e-8})
        {
            SCOPED_TRACE(testing::Message() << (planar ? "SE2, turn " : "SE3, turn ") << turn);
            const std::vector<RigidTransform> start{RigidTransform()};
            const std::vector<RigidTransform> goal{
                planar ? RigidTransform::fromPlanarPose(0.0, 0.0, turn)
                       : RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3(0.0, 0.0, 1.0), turn)};
            const SceneMotionResult sampled = checkSceneMotionBySampling(scene, start, goal, 2000, context);
            ASSERT_EQ(sampled.valid, turn < 0.0);  // only turning up crosses the speck
            SceneMotionOptions options;
            options.planar = planar;
            options.contactTolerance = 1e-12;  // the speck is 2.7e-9 from the needle, the default 2.2e-9
            const SceneMotionResult exact = checkSceneMotion(scene, start, goal, context, options);
            // In SE(3) a turn this small is certified for its whole angle at every t (OMPL keeps the
            // start rotation to the end): the speck 2.7e-9 below the turning needle is within it.
            EXPECT_EQ(exact.valid, sampled.valid && planar);
            if (!exact.valid && !sampled.valid)
                EXPECT_LE(exact.lastValidTime, sampled.contactTime);
        }
}

TEST(SceneMotion, TranslationLpMatchesAdvancement)
{
    // Box robots translating among boxes and hulls: the time-augmented LP decides those pairs;
    // advancement alone must give the same verdicts (up to the contact tolerance).
    std::vector<SceneBody> bodies;
    auto body = [&](std::string label, Shape shape, int robot, Vec3 at = Vec3::Zero()) {
        bodies.push_back({std::move(label), std::make_shared<const BodyGeometry>(std::move(shape)), robot,
                          RigidTransform{Mat3::Identity(), at}});
    };
    body("robot", Shape::box(Vec3(0.5, 0.3, 0.4)), 0);
    body("robot.2", Shape::convex({Vec3(0, 0, 0), Vec3(0.8, 0, 0), Vec3(0, 0.8, 0), Vec3(0, 0, 0.8)}), 1);
    body("obstacle.1", Shape::box(Vec3(0.1, 3.0, 3.0)), -1, Vec3(0.0, 0.0, 0.0));  // a thin wall
    body("obstacle.2", Shape::box(Vec3(1.0, 1.0, 1.0)), -1, Vec3(3.0, 3.0, 0.0));
    const Scene scene(std::move(bodies), 2, {});
    TestRandom rng(test::seeded(76));
    std::uniform_real_distribution<double> coordinate(-4.0, 4.0);
    QueryContext context;
    SceneMotionOptions withoutLp;
    withoutLp.translationLp = false;
    int rejected = 0, thinWall = 0;
    const int n = test::cases(300);
    for (int i = 0; i < n; ++i)
    {
        std::vector<RigidTransform> start(2), goal(2);
        for (std::size_t r = 0; r < 2; ++r)
        {
            const Mat3 rotation = test::randomRotation(rng);
            start[r] = {rotation, Vec3(coordinate(rng), coordinate(rng), coordinate(rng))};
            goal[r] = {rotation, Vec3(coordinate(rng), coordinate(rng), coordinate(rng))};
        }
        if (scene.collides(start, context))
            continue;
        const SceneMotionResult lp = checkSceneMotion(scene, start, goal, context);
        const SceneMotionResult advanced = checkSceneMotion(scene, start, goal, context, withoutLp);
        ASSERT_GT(lp.lpPairs, 0u);
        ASSERT_EQ(lp.valid, advanced.valid) << "motion " << i;
        if (!lp.valid)
        {
            ++rejected;
            // Both find the first contact; advancement stops within its tolerance of it.
            ASSERT_NEAR(lp.contactTime, advanced.contactTime, 1e-4) << "motion " << i;
        }
        // Ends on both sides of the thin wall: a sampled check could tunnel, these may not.
        thinWall += (start[0].translation.x() < -0.6 && goal[0].translation.x() > 0.6) ? 1 : 0;
    }
    EXPECT_GT(rejected, 0);
    EXPECT_GT(thinWall, 0);
}

TEST(Scene, AllowedPairsAndSelfPairs)
{
    std::vector<SceneBody> bodies;
    auto body = [&](std::string label, Shape shape, int robot, Vec3 at) {
        bodies.push_back({std::move(label), std::make_shared<const BodyGeometry>(std::move(shape)), robot,
                          RigidTransform{Mat3::Identity(), at}});
    };
    // A robot of two overlapping parts, resting on an obstacle it is allowed to touch.
    body("robot", Shape::sphere(1.0), 0, Vec3::Zero());
    body("robot.arm", Shape::capsule(0.3, 1.0), 0, Vec3(0.8, 0.0, 0.0));
    body("obstacle.1", Shape::box(Vec3(2.0, 2.0, 0.5)), -1, Vec3(0.0, 0.0, -1.4));
    const std::vector<RigidTransform> pose{RigidTransform()};
    QueryContext context;
    {
        const Scene scene(bodies, 1, {});
        EXPECT_TRUE(scene.collides(pose, context));  // the sphere rests on the box
        EXPECT_EQ(scene.pairs().size(), 2u);         // no self-pair by default
    }
    {
        const Scene scene(bodies, 1, {{0, 2}, {1, 2}});
        EXPECT_FALSE(scene.collides(pose, context));
        EXPECT_TRUE(scene.pairs().empty());
    }
    {
        SceneOptions options;
        options.selfCollision = true;
        const Scene scene(bodies, 1, {{0, 2}, {1, 2}}, options);
        EXPECT_TRUE(scene.collides(pose, context));  // the two parts overlap
        ASSERT_EQ(scene.pairs().size(), 1u);
    }
}

TEST(Scene, RejectsMalformedScenes)
{
    auto sphere = std::make_shared<const BodyGeometry>(Shape::sphere(1.0));
    const std::vector<std::pair<std::size_t, std::size_t>> none;
    EXPECT_THROW(Scene({{"robot", nullptr, 0, {}}}, 1, none), std::invalid_argument);
    EXPECT_THROW(Scene({{"robot", sphere, 2, {}}}, 1, none), std::invalid_argument);
    EXPECT_THROW(Scene({{"obstacle", sphere, -1, {}}}, 1, none), std::invalid_argument);  // robot 0 has no body
    EXPECT_THROW(Scene({{"robot", sphere, 0, {}}}, 1, {{0, 5}}), std::invalid_argument);
}

// Every scene key error names the file and line.
void expectError(const std::string &text, int line, const std::string &fragment)
{
    try
    {
        parseProblemConfig(text, "scene.cfg");
        FAIL() << "expected an error about '" << fragment << "'";
    }
    catch (const InputError &e)
    {
        const std::string message = e.what();
        EXPECT_NE(message.find("scene.cfg:" + std::to_string(line) + ":"), std::string::npos) << message;
        EXPECT_NE(message.find(fragment), std::string::npos) << message;
    }
}

const char *kHead = "[problem]\nrobot = r.obj\nstart.x = 0\nstart.y = 0\ngoal.x = 1\ngoal.y = 1\n";  // 6 lines

TEST(SceneConfig, ReadsRobotsObstaclesAndAllowedPairs)
{
    const ProblemConfig cfg =
        parseProblemConfig(std::string(kHead) + "robot.2 = capsule 0.5 2\nstart.2.x = 3\nstart.2.y = 4\n"
                                                "start.2.theta = 1\ngoal.2.x = 5\ngoal.2.y = 6\n"
                                                "obstacle.1 = box 1 2 3\nobstacle.1.x = 7\n"
                                                "obstacle.2 = convex hull.obj\n"
                                                "obstacle.3 = halfspace 0 1 0 -2\n"
                                                "allowed_collisions = robot.2 obstacle.1; robot obstacle.3\n",
                           "/tmp/scene.cfg");
    EXPECT_TRUE(cfg.isScene());
    EXPECT_TRUE(cfg.warnings.empty());
    ASSERT_EQ(cfg.extraRobots.size(), 1u);
    EXPECT_EQ(cfg.extraRobots[0].shape.kind, "capsule");
    EXPECT_EQ(cfg.extraRobots[0].shape.parameters, (std::vector<double>{0.5, 2.0}));
    EXPECT_EQ(cfg.extraRobots[0].start.theta, 1.0);
    EXPECT_EQ(cfg.extraRobots[0].goal.y, 6.0);
    ASSERT_EQ(cfg.obstacles.size(), 3u);
    EXPECT_EQ(cfg.obstacles[0].pose.x, 7.0);
    EXPECT_EQ(cfg.obstacles[1].shape.kind, "convex");
    EXPECT_EQ(cfg.obstacles[1].shape.file, "/tmp/hull.obj");
    ASSERT_EQ(cfg.allowedCollisions.size(), 2u);
    EXPECT_EQ(cfg.allowedCollisions[1].first, "robot");
    // A problem of one robot is no scene.
    EXPECT_FALSE(parseProblemConfig(kHead, "/tmp/one.cfg").isScene());
}

TEST(SceneConfig, ErrorsNameTheLine)
{
    const std::string head = kHead;
    expectError(head + "robot.2 = sphere 1\nstart.2.x = 1\nstart.2.y = 1\n", 7, "goal.2.x");
    expectError(head + "start.3.x = 1\n", 7, "no 'robot.3");
    expectError(head + "obstacle.4.x = 1\n", 7, "no 'obstacle.4");
    expectError(head + "obstacle.1 = box 1 2\n", 7, "takes 3 numbers");
    expectError(head + "obstacle.1 = sphere -1\n", 7, "positive");
    expectError(head + "obstacle.1 = halfspace 0 0 0 1\n", 7, "non-zero normal");
    // Dimensions whose squares would overflow or underflow.
    expectError(head + "obstacle.1 = capsule 1e308 1e308\n", 7, "magnitude at most 1e100, got '1e308'");
    expectError(head + "obstacle.1 = sphere 1e-200\n", 7, "magnitude 1e-100 to 1e100");
    expectError(head + "obstacle.1 = halfspace 1 0 0 1e150\n", 7, "magnitude at most 1e100");
    expectError(head + "obstacle.1 = mesh\n", 7, "needs a mesh file");
    expectError(head + "obstacle.1 = sphere 1\nallowed_collisions = robot obstacle.2\n", 8, "obstacle.2");
    expectError(head + "obstacle.1 = sphere 1\nallowed_collisions = robot\n", 8, "pairs of body names");
    expectError(head + "obstacle.1 = sphere 1\nobstacle.1.z = 2\n", 8, "planar problem");
    expectError(head + "robot.2 = halfspace 0 0 1 0\nstart.2.x = 1\nstart.2.y = 1\ngoal.2.x = 1\ngoal.2.y = 1\n", 7,
                "cannot be a halfspace");
}
}  // namespace
}  // namespace hcd
