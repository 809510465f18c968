// SPDX-License-Identifier: BSD-3-Clause
// withinSweptDistance is what continuous motion checking rests on: "false" must prove that no robot
// point p comes within translationSlack + radialSlack * |p| of the environment. Checked here for
// every checker against exact point-to-triangle distances on points sampled densely over the robot's
// surface, and along motions against brute-force collision checks at many poses of each certified
// interval.
#include "support/test_support.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/query/checker_catalogue.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
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

TEST(SweptDistance, FalseProvesEveryRobotPointIsBeyondItsReach)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    const TriangleMesh &robot = *problem.robot.mesh, &environment = *problem.world.mesh;
    const double radius = robot.radiusAboutOrigin();
    const std::vector<Vec3> samples = surfaceSamples(robot, 4);
    test::TestRandom rng(test::seeded(31));
    const auto poses = test::randomPoses(problem, 240, rng);
    std::uniform_real_distribution<double> slack(0.0, 0.5), radial(0.0, 0.03);
    const auto reference = makeChecker("bruteforce", problem.scene);
    for (const std::string &name : CheckerCatalogue::builtIn().names())
    {
        const auto checker = makeChecker(name, problem.scene);
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

TEST(SweptDistance, CertifiedMotionIntervalsAreFreeUnderDenseSampling)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    const double radius = problem.robot.mesh->radiusAboutOrigin();
    test::TestRandom rng(test::seeded(32));
    const auto starts = test::randomPoses(problem, 120, rng);
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
