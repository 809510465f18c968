// SPDX-License-Identifier: BSD-3-Clause
// The brute-force reference is itself a sweep over x-sorted boxes; here it is checked against the
// plainest possible reference, every robot triangle against every environment triangle, on random
// triangle soups and on adversarial ones (shared vertices, coplanar and touching triangles, huge
// and tiny scales).
#include "support/test_support.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/query/checker_catalogue.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

using namespace hcd;

namespace
{
struct AllPairs
{
    bool collides = false;
    std::size_t intersectingPairs = 0;
    double distance = std::numeric_limits<double>::infinity();
};

// Every pair, no culling: the answer by definition.
AllPairs allPairs(const TriangleMesh &robot, const TriangleMesh &environment, const RigidTransform &pose)
{
    AllPairs r;
    for (std::uint32_t i = 0; i < robot.triangleCount(); ++i)
    {
        const Vec3 a0 = pose.apply(robot.corner(i, 0)), a1 = pose.apply(robot.corner(i, 1)),
                   a2 = pose.apply(robot.corner(i, 2));
        for (std::uint32_t j = 0; j < environment.triangleCount(); ++j)
        {
            const Vec3 &b0 = environment.corner(j, 0), &b1 = environment.corner(j, 1), &b2 = environment.corner(j, 2);
            if (trianglesIntersect(a0, a1, a2, b0, b1, b2))
            {
                r.collides = true;
                ++r.intersectingPairs;
                r.distance = 0.0;
            }
            else
                r.distance = std::min(r.distance, triangleDistance(a0, a1, a2, b0, b1, b2));
        }
    }
    return r;
}

// `count` random triangles of size about `size` in the cube [-extent, extent]^3. With `snap`, the
// coordinates are small integers times `size`, so that shared vertices, coplanar triangles and exact
// touching are common.
TriangleMesh triangleSoup(std::size_t count, double extent, double size, bool snap, test::TestRandom &rng)
{
    std::uniform_real_distribution<double> centre(-extent, extent), offset(-size, size);
    std::uniform_int_distribution<int> grid(-1, 1);
    TriangleMesh mesh;
    for (std::size_t t = 0; t < count; ++t)
    {
        const Vec3 c(centre(rng), centre(rng), centre(rng));
        for (int k = 0; k < 3; ++k)
        {
            const Vec3 d =
                snap ? size * Vec3(grid(rng), grid(rng), grid(rng)) : Vec3(offset(rng), offset(rng), offset(rng));
            const Vec3 snapped =
                size * Vec3(std::round(c.x() / size), std::round(c.y() / size), std::round(c.z() / size));
            mesh.vertices.push_back(snap ? Vec3(snapped + d) : Vec3(c + d));
        }
        const std::uint32_t base = std::uint32_t(3 * t);
        mesh.triangles.push_back({base, base + 1, base + 2});
    }
    return mesh;
}

void compareOnSoups(double scale, bool snap, std::uint64_t seed, int scenes)
{
    test::TestRandom rng(test::seeded(seed));
    std::size_t colliding = 0, free = 0;
    for (int scene = 0; scene < scenes; ++scene)
    {
        CollisionScene s;
        s.robot = std::make_shared<const TriangleMesh>(triangleSoup(25, 1.0 * scale, 0.4 * scale, snap, rng));
        s.environment = std::make_shared<const TriangleMesh>(triangleSoup(60, 3.0 * scale, 0.6 * scale, snap, rng));
        const auto bruteForce = makeChecker("bruteforce", s, ContactSemantics::SurfaceOnly);
        std::uniform_real_distribution<double> u(-3.0 * scale, 3.0 * scale);
        std::uniform_int_distribution<int> grid(-8, 8);
        for (int p = 0; p < 40; ++p)
        {
            // Snapped scenes keep the identity rotation and grid translations, so exact contacts stay exact.
            const RigidTransform pose =
                snap ? RigidTransform{Mat3::Identity(), 0.4 * scale * Vec3(grid(rng), grid(rng), grid(rng))}
                     : RigidTransform{test::randomRotation(rng), Vec3(u(rng), u(rng), u(rng))};
            const AllPairs expected = allPairs(*s.robot, *s.environment, pose);
            (expected.collides ? colliding : free) += 1;
            ASSERT_EQ(bruteForce->collides(pose), expected.collides)
                << "scale " << scale << (snap ? " snapped" : "") << " scene " << scene << " pose " << p;
            ASSERT_EQ(bruteForce->contacts(pose, 1u << 20).size(), expected.intersectingPairs);
            const double d = bruteForce->distance(pose);
            if (expected.collides)
                ASSERT_EQ(d, 0.0);
            else
                ASSERT_NEAR(d, expected.distance, 1e-12 * scale) << "scale " << scale;
        }
    }
    // Both outcomes common, or the comparison proves little.
    EXPECT_GT(colliding, std::size_t(scenes) * 5) << "scale " << scale;
    EXPECT_GT(free, std::size_t(scenes) * 5) << "scale " << scale;
}
}  // namespace

TEST(BruteForce, SweepMatchesAllPairsOnRandomSoups)
{
    for (double scale : {1e-9, 1.0, 1e9})
        compareOnSoups(scale, false, 11, 12);
}

TEST(BruteForce, SweepMatchesAllPairsOnSnappedSoups)
{
    // Grid coordinates: many shared vertices, coplanar (z = const) triangles and exact touching.
    for (double scale : {1e-9, 1.0, 1e9})
        compareOnSoups(scale, true, 12, 4);  // exact arithmetic decides most pairs here: slower
}

TEST(BruteForce, NonFinitePosesCollideForEveryChecker)
{
    CollisionScene s;
    s.robot = std::make_shared<const TriangleMesh>(test::boxMesh(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
    s.environment = std::make_shared<const TriangleMesh>(test::boxMesh(Vec3(10, 10, 10), Vec3(11, 11, 11)));
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    Mat3 nanRotation = Mat3::Identity();
    nanRotation(1, 2) = nan;
    for (const std::string &name : CheckerCatalogue::builtIn().names())
    {
        const auto checker = makeChecker(name, s);
        for (const RigidTransform &pose :
             {RigidTransform{Mat3::Identity(), Vec3(nan, 0, 0)}, RigidTransform{Mat3::Identity(), Vec3(0, -inf, 0)},
              RigidTransform{nanRotation, Vec3(0, 0, 0)}})
        {
            EXPECT_TRUE(checker->collides(pose)) << name;
            EXPECT_EQ(checker->distance(pose), 0.0) << name;
            EXPECT_TRUE(checker->withinDistance(pose, 0.0)) << name;
            EXPECT_TRUE(checker->withinSweptDistance(pose, 0.0, 0.0, 1.0)) << name;
        }
        EXPECT_FALSE(checker->collides({Mat3::Identity(), Vec3(0, 0, 0)})) << name;
    }
}
