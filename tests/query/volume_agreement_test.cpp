// SPDX-License-Identifier: BSD-3-Clause
// Every catalogue checker answers as bruteforce for collides, distance and contacts, on uniform
// poses and on poses within 1e-9 of contact (pairs found by bisection: one touching or
// overlapping, one free), on OMPL.app problems. Near contact is where a volume test that says
// "apart" wrongly, or a distance bound above the truth, shows.
#include "support/test_support.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/query/brute_force_checker.h"
#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/query/volume_tree_checker.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

using namespace hcd;

namespace
{
using ContactKey = std::tuple<int, std::uint32_t, std::uint32_t>;

std::vector<ContactKey> keysOf(const std::vector<ContactPair> &contacts)
{
    std::vector<ContactKey> keys;
    for (const ContactPair &c : contacts)
        keys.emplace_back(int(c.kind), c.robotElement, c.environmentElement);
    std::sort(keys.begin(), keys.end());
    return keys;
}

// Pairs of poses with one rotation and translations at most 1e-9 apart, the first colliding and
// the second free (by `guide`, which the agreement test elsewhere checks against bruteforce; the
// answers here are compared with bruteforce itself). From colliding random poses the robot is
// moved straight out of the environment's bounding sphere, and the segment bisected.
std::vector<RigidTransform> nearContactPoses(const LoadedProblem &problem, const CollisionChecker &guide,
                                             std::size_t pairs, test::TestRandom &rng)
{
    const double reach =
        2.0 * (problem.scene.environment->radiusAboutOrigin() + problem.scene.robot->radiusAboutOrigin());
    std::vector<RigidTransform> out;
    for (const RigidTransform &pose : test::randomPoses(problem, 40 * pairs, rng))
    {
        if (out.size() >= 2 * pairs)
            break;
        if (!guide.collides(pose))
            continue;
        Vec3 direction = test::randomRotation(rng).col(0);
        if (problem.config.planar)
            direction.z() = 0.0;
        if (!(direction.norm() > 0.1))
            continue;
        const Vec3 far = pose.translation + (reach + pose.translation.norm()) * direction.normalized();
        Vec3 in = pose.translation, outside = far;
        if (guide.collides({pose.rotation, outside}))
            continue;
        while ((outside - in).norm() > 1e-9)
        {
            const Vec3 mid = 0.5 * (in + outside);
            if (mid == in || mid == outside)
                break;
            (guide.collides({pose.rotation, mid}) ? in : outside) = mid;
        }
        out.push_back({pose.rotation, in});
        out.push_back({pose.rotation, outside});
    }
    return out;
}

void checkProblem(const std::string &cfg, std::size_t uniformCount, std::size_t distanceCount, std::size_t nearPairs,
                  const std::vector<std::string> &skipped = {})
{
    const std::string relative = std::filesystem::path(cfg).filename().string();
    const LoadedProblem problem = loadProblem(cfg);
    test::TestRandom rng(test::seeded(1913));
    const auto reference = makeChecker("bruteforce", problem.scene);
    const auto uniform = test::randomPoses(problem, uniformCount, rng);
    const auto near = nearContactPoses(problem, *makeChecker("obb", problem.scene), nearPairs, rng);
    ASSERT_GE(near.size(), nearPairs) << relative;  // enough colliding poses to start from

    // The reference answers, once.
    struct Expected
    {
        bool collides;
        std::vector<ContactKey> contacts;
        double distance = -1.0;  ///< computed for the first poses of each kind only (it is O(pairs))
    };
    std::vector<RigidTransform> poses = uniform;
    poses.insert(poses.end(), near.begin(), near.end());
    std::vector<Expected> expected;
    std::size_t colliding = 0, nearFree = 0;
    for (std::size_t i = 0; i < poses.size(); ++i)
    {
        const bool isNear = i >= uniform.size();
        const bool withDistance = isNear ? (i - uniform.size()) < 2 * distanceCount : i < distanceCount;
        Expected e{reference->collides(poses[i]), keysOf(reference->contacts(poses[i], 1000000))};
        if (withDistance)
            e.distance = reference->distance(poses[i]);
        colliding += e.collides ? 1 : 0;
        if (isNear && !e.collides)
        {
            ++nearFree;
            if (withDistance)
                EXPECT_LE(e.distance, 1e-8) << "the free pose of a pair is within 1e-9 of contact";
        }
        expected.push_back(std::move(e));
    }
    EXPECT_GT(colliding, poses.size() / 10) << relative;
    EXPECT_GE(nearFree, near.size() / 2 - near.size() / 20) << relative;

    for (const std::string &name : CheckerCatalogue::builtIn().names())
    {
        if (name == "bruteforce" || std::find(skipped.begin(), skipped.end(), name) != skipped.end())
            continue;
        const auto start = std::chrono::steady_clock::now();
        const auto checker = makeChecker(name, problem.scene);
        std::size_t wrong = 0;
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            const Expected &e = expected[i];
            const char *kind = i < uniform.size() ? "uniform" : "near-contact";
            const bool collides = checker->collides(poses[i]);
            EXPECT_EQ(collides, e.collides) << name << " collides, " << kind << " pose " << i << " of " << relative;
            EXPECT_EQ(keysOf(checker->contacts(poses[i], 1000000)), e.contacts)
                << name << " contacts, " << kind << " pose " << i << " of " << relative;
            if (e.distance >= 0.0)
                EXPECT_EQ(checker->distance(poses[i]), e.distance)
                    << name << " distance, " << kind << " pose " << i << " of " << relative;
            wrong += collides != e.collides ? 1 : 0;
        }
        std::cout << "[ agreement ] " << name << " vs bruteforce on " << std::filesystem::path(cfg).filename().string()
                  << ": " << uniform.size() << " uniform and " << near.size()
                  << " near-contact poses (collides, contacts; distance on a subset), " << wrong
                  << " collision disagreements, "
                  << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
    }
}
}  // namespace

// 400 uniform poses and 100 near-contact pairs per problem; distance on 10 of each kind, on the
// OMPL.app problems of bench/README.md (Apartment, larger, below).
#define HCD_AGREEMENT(Name, relative)                                                                                  \
    TEST(VolumeAgreement, Name)                                                                                        \
    {                                                                                                                  \
        HYBRIDCD_REQUIRE_OMPLAPP(cfg, relative);                                                                       \
        checkProblem(cfg, test::cases(400), 10, test::cases(100));                                                     \
    }
HCD_AGREEMENT(Cubicles, "3D/cubicles.cfg")
HCD_AGREEMENT(Twistycool, "3D/Twistycool.cfg")
HCD_AGREEMENT(Alpha15, "3D/alpha-1.5.cfg")
HCD_AGREEMENT(Easy, "3D/Easy.cfg")
HCD_AGREEMENT(Home, "3D/Home.cfg")
HCD_AGREEMENT(Bugtrap, "3D/bugtrap.cfg")
HCD_AGREEMENT(Abstract, "3D/Abstract.cfg")
HCD_AGREEMENT(MazePlanar, "2D/Maze_planar.cfg")
HCD_AGREEMENT(BugTrapPlanar, "2D/BugTrap_planar.cfg")

// Apartment (18k distinct environment triangles against 1.6k of the robot's): the reference
// visits all 30M triangle pairs for each contact list and distance (about 0.1 s per pose), and
// the ellipsoid, hybrid and lp checkers take about a second each to build, so fewer poses here:
// 40 uniform and 20 near-contact pairs, distance on 2 of each kind (about 15 s in all). Every
// checker of the catalogue takes part in Release builds. Under the sanitizers those four take
// 10-40 s each to build (minimum-volume ellipsoids per node; convex pieces), 90 of the test's
// 140 s, so they are left to the Release run there; the others run on the sanitizers' poses.
TEST(VolumeAgreement, Apartment)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/Apartment.cfg");
    std::vector<std::string> skipped;
    if (test::kSanitizerCaseDivisor > 1)
        skipped = {"ellipsoid", "hybrid", "hybrid-ellipsoid-first", "lp"};
    checkProblem(cfg, test::cases(40), 2, test::cases(20), skipped);
}
// The project's organic problems (smooth closed meshes of thousands of triangles, where brute
// force is slow): fewer poses, and distances only on the OMPL.app problems above. Under the
// sanitizers the ellipsoid, hybrid and lp builds take 50 of each test's 80 s there; the OMPL.app
// problems above still run them under the sanitizers, and the Release run checks them here.
std::vector<std::string> skippedOnOrganicUnderSanitizers()
{
    if (test::kSanitizerCaseDivisor == 1)
        return {};
    return {"ellipsoid", "hybrid", "hybrid-ellipsoid-first", "lp"};
}
#define HCD_ORGANIC_AGREEMENT(Name, relative)                                                                          \
    TEST(VolumeAgreement, Name)                                                                                        \
    {                                                                                                                  \
        checkProblem(test::sourcePath(relative), test::cases(16), 0, test::cases(4),                                   \
                     skippedOnOrganicUnderSanitizers());                                                               \
    }
HCD_ORGANIC_AGREEMENT(OrganicBone3d, "problems/bone_3d.cfg")
HCD_ORGANIC_AGREEMENT(OrganicRibcage3d, "problems/ribcage_3d.cfg")
HCD_ORGANIC_AGREEMENT(OrganicBones2d, "problems/bones_2d.cfg")

namespace
{
// A closed torus about the z axis: `rings` x `sides` quads, two triangles each.
TriangleMesh torusMesh(double major, double minor, int rings, int sides)
{
    TriangleMesh m;
    const double turn = 2.0 * 3.14159265358979323846;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < sides; ++j)
        {
            const double u = turn * i / rings, v = turn * j / sides;
            m.vertices.emplace_back((major + minor * std::cos(v)) * std::cos(u),
                                    (major + minor * std::cos(v)) * std::sin(u), minor * std::sin(v));
        }
    const auto at = [&](int i, int j) { return std::uint32_t((i % rings) * sides + j % sides); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < sides; ++j)
        {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}
}  // namespace

// Two like parts (a torus against a copy of itself, the alpha puzzle's kind of scene): the
// traversals split both nodes of a pair at once there, and only there, and still give
// bruteforce's answers: the distance on every pose, linked rings and near misses included (an
// exact match, as above), collisions, and proximity within a few distances.
TEST(VolumeAgreement, LikePartsDescendInLockstepAndStayExact)
{
    const auto torus = std::make_shared<const TriangleMesh>(torusMesh(1.0, 0.25, 16, 8));
    const CollisionScene alike{torus, torus, "torus", "torus"};
    const ObbTreeChecker lockstep(alike, "obb");
    ASSERT_TRUE(lockstep.descendsInLockstep());
    const CollisionScene unlike{std::make_shared<const TriangleMesh>(test::boxMesh(Vec3::Zero(), Vec3::Ones())), torus,
                                "box", "torus"};
    EXPECT_FALSE(ObbTreeChecker(unlike, "obb").descendsInLockstep());

    const BruteForceChecker reference(alike);
    test::TestRandom rng(test::seeded(4411));
    std::uniform_real_distribution<double> offset(-0.6, 0.6), slack(0.0, 0.3);
    // Swept proximity measures every triangle pair per pose: a fixed number of poses, the same
    // under the sanitizers, so that both answers occur there too.
    constexpr int kSweptPoses = 24;
    std::size_t free = 0, swept[2] = {0, 0}, listedPoses = 0;
    for (int i = 0; i < std::max(test::cases(300), kSweptPoses); ++i)
    {
        // Half the poses link the rings (the copy turned a quarter about x and shifted by its
        // major radius), the others are turned at random near the first.
        RigidTransform pose;
        if (i % 2 == 0)
        {
            pose.rotation =
                Eigen::AngleAxisd(0.5 * 3.14159265358979323846 + 0.3 * offset(rng), Vec3::UnitX()).toRotationMatrix();
            pose.translation = Vec3(1.0 + offset(rng), 0.5 * offset(rng), 0.5 * offset(rng));
        }
        else
        {
            pose.rotation = test::randomRotation(rng);
            pose.translation = Vec3(2.0 * offset(rng), 2.0 * offset(rng), 2.0 * offset(rng));
        }
        const double expected = reference.distance(pose);
        free += expected > 0.0 ? 1 : 0;
        ASSERT_EQ(lockstep.distance(pose), expected) << "pose " << i;
        ASSERT_EQ(lockstep.collides(pose), reference.collides(pose)) << "pose " << i;
        ASSERT_EQ(keysOf(lockstep.contacts(pose, 1000000)), keysOf(reference.contacts(pose, 1000000))) << "pose " << i;
        for (const double delta : {0.5 * expected, expected, 2.0 * expected + 1e-3})
            ASSERT_EQ(lockstep.withinDistance(pose, delta), reference.withinDistance(pose, delta))
                << "pose " << i << ", delta " << delta;
        if (i >= kSweptPoses)
            continue;
        // Swept proximity (each robot triangle's reach grows with its distance from the robot
        // origin) against every triangle pair measured directly; ties within rounding are skipped.
        const double translation = 0.25 * slack(rng), radial = 0.05 * slack(rng);
        double margin = std::numeric_limits<double>::infinity();  // least distance beyond reach
        std::vector<std::pair<std::uint32_t, std::uint32_t>> nearPairs;
        bool tied = false;  // some pair within rounding of its reach: the list is left unchecked
        for (std::size_t a = 0; a < torus->triangleCount(); ++a)
        {
            const Vec3 a0 = pose.apply(torus->corner(a, 0)), a1 = pose.apply(torus->corner(a, 1)),
                       a2 = pose.apply(torus->corner(a, 2));
            const double reach =
                translation +
                radial * std::max({torus->corner(a, 0).norm(), torus->corner(a, 1).norm(), torus->corner(a, 2).norm()});
            for (std::size_t b = 0; b < torus->triangleCount(); ++b)
            {
                const double beyond =
                    triangleDistance(a0, a1, a2, torus->corner(b, 0), torus->corner(b, 1), torus->corner(b, 2)) - reach;
                margin = std::min(margin, beyond);
                tied = tied || std::abs(beyond) <= 1e-8;
                if (beyond <= 0.0)
                    nearPairs.emplace_back(std::uint32_t(a), std::uint32_t(b));
            }
        }
        // The near-pair list: every pair within its reach, no other.
        std::vector<TrianglePair> listed;
        QueryContext context;
        if (!tied && (translation > 0.0 || radial > 0.0))
        {
            ASSERT_TRUE(lockstep.listSweptNearPairs(pose, translation, radial, 1u << 20, listed, context));
            std::vector<std::pair<std::uint32_t, std::uint32_t>> got;
            for (const TrianglePair &p : listed)
                got.emplace_back(p.robot, p.environment);
            std::sort(got.begin(), got.end());
            ASSERT_EQ(got, nearPairs) << "pose " << i;
            ++listedPoses;
        }
        // The checker grows each reach by a relative 1e-9 and a tolerance near 1e-12 of the
        // coordinates, far inside this band.
        if (std::abs(margin) > 1e-8)
        {
            ++swept[margin <= 0.0 ? 1 : 0];
            ASSERT_EQ(lockstep.withinSweptDistance(pose, translation, radial, torus->radiusAboutOrigin()),
                      margin <= 0.0)
                << "pose " << i << ", margin " << margin;
        }
    }
    // Both swept answers occur, or that part proves little.
    EXPECT_GT(swept[0], 2u);
    EXPECT_GT(swept[1], 2u);
    EXPECT_GT(listedPoses, std::size_t(kSweptPoses / 2));
    std::cout << "[ like parts ] swept answers: " << swept[0] << " beyond reach, " << swept[1] << " within; "
              << listedPoses << " near-pair lists compared\n";
    EXPECT_GT(free, std::size_t(test::cases(300) / 5));
}

// A mesh without triangles on either side: every tree checker builds (no lanes, no grid) and finds
// nothing, as bruteforce does.
TEST(VolumeAgreement, EmptyMeshesTouchNothing)
{
    const auto box = std::make_shared<const TriangleMesh>(test::boxMesh(Vec3::Zero(), Vec3::Ones()));
    const auto empty = std::make_shared<const TriangleMesh>();
    const RigidTransform pose{Mat3::Identity(), Vec3(0.25, 0.0, 0.0)};
    for (const CollisionScene &scene :
         {CollisionScene{box, empty, "box", "empty"}, CollisionScene{empty, box, "empty", "box"}})
        for (const char *name : {"obb", "aabb", "kdop18", "auto"})
        {
            SCOPED_TRACE(std::string(name) + ", robot " + scene.robotName);
            const std::unique_ptr<CollisionChecker> checker = makeChecker(name, scene);
            EXPECT_FALSE(checker->collides(pose));
            EXPECT_EQ(checker->distance(pose), std::numeric_limits<double>::infinity());
            EXPECT_TRUE(checker->contacts(pose, 4).empty());
            EXPECT_EQ(BruteForceChecker(scene).collides(pose), false);
        }
}
