// SPDX-License-Identifier: BSD-3-Clause
// The first contact of a translating robot (time-augmented LP on triangle pairs) against three
// references: the same LP on every pair without culling, closed-form contact times of boxes, and
// dense sampling of the motion with the brute-force checker.
#include "support/test_support.h"

#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/query/translation_contact.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace hcd;

namespace
{
CollisionScene sceneOf(TriangleMesh robot, TriangleMesh environment)
{
    return {std::make_shared<const TriangleMesh>(std::move(robot)),
            std::make_shared<const TriangleMesh>(std::move(environment)), "robot", "environment"};
}

TriangleMesh soup(std::size_t count, double extent, double size, test::TestRandom &rng)
{
    std::uniform_real_distribution<double> centre(-extent, extent), offset(-size, size);
    TriangleMesh mesh;
    for (std::size_t t = 0; t < count; ++t)
    {
        const Vec3 c(centre(rng), centre(rng), centre(rng));
        for (int k = 0; k < 3; ++k)
            mesh.vertices.push_back(c + Vec3(offset(rng), offset(rng), offset(rng)));
        const std::uint32_t base = std::uint32_t(3 * t);
        mesh.triangles.push_back({base, base + 1, base + 2});
    }
    return mesh;
}

RigidTransform translatedBy(const RigidTransform &pose, const Vec3 &offset)
{
    RigidTransform moved = pose;
    moved.translation += offset;
    return moved;
}
}  // namespace

TEST(TranslationContact, BoxesMeetAtTheClosedFormTime)
{
    // A unit cube moving along +x towards a cube 3 units ahead: the faces meet after a gap of 2.
    const TranslationContactFinder finder(
        sceneOf(test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1)), test::boxMesh(Vec3(3, 0.25, 0.25), Vec3(4, 0.75, 0.75))));
    for (double length : {2.0, 2.5, 4.0, 10.0})
    {
        const TranslationContact c = finder.firstContact(RigidTransform(), Vec3(length, 0, 0));
        ASSERT_TRUE(c.contact) << length;
        EXPECT_NEAR(c.time, 2.0 / length, 1e-9) << length;
        EXPECT_NEAR(c.point.x(), 3.0, 1e-9);
    }
    EXPECT_FALSE(finder.firstContact(RigidTransform(), Vec3(1.99, 0, 0)).contact);
    EXPECT_FALSE(finder.firstContact(RigidTransform(), Vec3(-5, 0, 0)).contact);
    // Passing beside it, 1e-6 clear of its side: no contact; and touching it exactly along the way.
    EXPECT_FALSE(finder.firstContact(translatedBy(RigidTransform(), Vec3(0, 0.75 + 1e-6, 0)), Vec3(9, 0, 0)).contact);
    const TranslationContact grazing =
        finder.firstContact(translatedBy(RigidTransform(), Vec3(0, 0.75, 0)), Vec3(9, 0, 0));
    ASSERT_TRUE(grazing.contact);
    EXPECT_NEAR(grazing.time, 2.0 / 9.0, 1e-9);
}

TEST(TranslationContact, AThinWallCannotBeTunnelledThrough)
{
    // One square of two triangles, crossed in a single step: both ends are free, the motion is not.
    TriangleMesh wall;
    wall.vertices = {Vec3(5, -10, -10), Vec3(5, 10, -10), Vec3(5, 10, 10), Vec3(5, -10, 10)};
    wall.triangles = {{0, 1, 2}, {0, 2, 3}};
    const TranslationContactFinder finder(sceneOf(test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1)), wall));
    for (double scale : {1e-6, 1.0, 1e6})
    {
        TriangleMesh robot = test::boxMesh(Vec3(0, 0, 0), Vec3(scale, scale, scale));
        TriangleMesh scaledWall = wall;
        for (Vec3 &v : scaledWall.vertices)
            v *= scale;
        const TranslationContactFinder scaled(sceneOf(robot, scaledWall));
        const TranslationContact c = scaled.firstContact(RigidTransform(), Vec3(100 * scale, 0, 0));
        ASSERT_TRUE(c.contact) << scale;
        EXPECT_NEAR(c.time, 4.0 / 100.0, 1e-9) << scale;
    }
    EXPECT_TRUE(finder.firstContact(RigidTransform(), Vec3(4, 0, 0)).contact);  // touching at the end
}

TEST(TranslationContact, CullingNeverChangesTheAnswer)
{
    test::TestRandom rng(test::seeded(41));
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::size_t contacts = 0, free = 0;
    // Fixed counts, sanitizer builds included: both outcomes must be common, and a case is cheap.
    for (int scene = 0; scene < 12; ++scene)
    {
        const TranslationContactFinder finder(sceneOf(soup(12, 1.0, 0.4, rng), soup(60, 3.0, 0.6, rng)));
        for (int motion = 0; motion < 20; ++motion)
        {
            RigidTransform pose;
            pose.rotation = test::randomRotation(rng);
            pose.translation = 3.0 * Vec3(unit(rng), unit(rng), unit(rng));
            const Vec3 d = 4.0 * Vec3(unit(rng), unit(rng), unit(rng));
            const TranslationContact fast = finder.firstContact(pose, d);
            const TranslationContact reference = finder.firstContactAllPairs(pose, d);
            ASSERT_EQ(fast.contact, reference.contact) << "scene " << scene << " motion " << motion;
            if (fast.contact)
            {
                // The same LP on the same earliest pair (or one that ties with it).
                EXPECT_EQ(fast.time, reference.time) << "scene " << scene << " motion " << motion;
                ++contacts;
            }
            else
                ++free;
            EXPECT_LE(fast.pairsSolved, reference.pairsSolved);
        }
    }
    EXPECT_GT(contacts, 20u);
    EXPECT_GT(free, 20u);
}

TEST(TranslationContact, AgreesWithDenseSamplingOfTheMotion)
{
    test::TestRandom rng(test::seeded(43));
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const CheckerCatalogue catalogue = CheckerCatalogue::builtIn();
    constexpr int kSamples = 400;
    std::size_t contacts = 0;
    for (int scene = 0; scene < 6; ++scene)
    {
        const CollisionScene collision = sceneOf(soup(10, 1.0, 0.5, rng), soup(80, 3.0, 0.7, rng));
        const TranslationContactFinder finder(collision);
        const auto bruteforce = catalogue.make("bruteforce", collision);
        for (int motion = 0; motion < 15; ++motion)
        {
            RigidTransform pose;
            pose.rotation = test::randomRotation(rng);
            pose.translation = 3.0 * Vec3(unit(rng), unit(rng), unit(rng));
            const Vec3 d = 3.0 * Vec3(unit(rng), unit(rng), unit(rng));
            const TranslationContact c = finder.firstContact(pose, d);
            // Every sample the brute-force checker finds colliding lies at or after the contact.
            for (int k = 0; k <= kSamples; ++k)
            {
                const double t = double(k) / kSamples;
                if (bruteforce->collides(translatedBy(pose, t * d)))
                {
                    ASSERT_TRUE(c.contact) << "scene " << scene << " motion " << motion << " t " << t;
                    // (The LP's time is exact up to rounding: about 1e-16 late on a start in contact.)
                    EXPECT_LE(c.time, t + 1e-12) << "scene " << scene << " motion " << motion;
                    break;
                }
            }
            if (c.contact)
            {
                ++contacts;
                // Just before the contact the robot is free; at it, the contact point lies on the
                // robot's surface moved by time * d, within rounding.
                if (c.time > 1e-6)
                    EXPECT_FALSE(bruteforce->collides(translatedBy(pose, (c.time - 1e-6) * d)))
                        << "scene " << scene << " motion " << motion;
                EXPECT_TRUE(bruteforce->withinDistance(translatedBy(pose, c.time * d), 1e-9))
                    << "scene " << scene << " motion " << motion;
            }
        }
    }
    EXPECT_GT(contacts, 10u);
}

TEST(TranslationContact, NonFiniteInputIsAContactNeverFree)
{
    const TranslationContactFinder finder(
        sceneOf(test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1)), test::boxMesh(Vec3(3, 0, 0), Vec3(4, 1, 1))));
    EXPECT_TRUE(finder.firstContact(RigidTransform(), Vec3(std::nan(""), 0, 0)).contact);
    RigidTransform bad;
    bad.translation.x() = std::numeric_limits<double>::infinity();
    EXPECT_TRUE(finder.firstContact(bad, Vec3(1, 0, 0)).contact);
}
