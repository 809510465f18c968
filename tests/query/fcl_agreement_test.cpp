// SPDX-License-Identifier: BSD-3-Clause
// FCL, set up as OMPL.app sets it up, against the brute-force reference on the same poses.
#include "support/test_support.h"

#include "hybridcd/fcl/fcl_checker.h"
#include "hybridcd/query/checker_catalogue.h"

#include <gtest/gtest.h>

using namespace hcd;

namespace
{
void compareWithFcl(const std::string &cfg)
{
    const LoadedProblem problem = loadProblem(cfg);
    test::TestRandom rng(99);
    const auto poses = test::randomPoses(problem, 3000, rng);
    const auto fcl = checkersWithFcl().make("fcl", problem.scene);
    const auto surface = makeChecker("bruteforce", problem.scene, ContactSemantics::SurfaceOnly);
    const auto solid = makeChecker("bruteforce", problem.scene, ContactSemantics::Solid);
    std::size_t colliding = 0, fclMissed = 0, fclExtra = 0, containment = 0;
    for (const RigidTransform &pose : poses)
    {
        const bool expected = surface->collides(pose), got = fcl->collides(pose);
        colliding += expected;
        fclMissed += expected && !got;
        fclExtra += !expected && got;
        // FCL treats meshes as surfaces: a robot inside a closed obstacle is "free" to it.
        if (!got && solid->collides(pose))
            ++containment;
    }
    // On random (never exactly touching) poses FCL agrees with the surface reference exactly; the
    // poses where only solid semantics see contact are counted apart.
    EXPECT_EQ(fclMissed, 0u) << cfg;
    EXPECT_EQ(fclExtra, 0u) << cfg;
    std::cout << "[ fcl ] " << cfg << ": " << poses.size() << " poses, " << colliding << " surface contacts, "
              << containment << " containments FCL calls free\n";
    EXPECT_GT(colliding, poses.size() / 10);
    EXPECT_LT(colliding, poses.size() * 9 / 10);
}
}  // namespace

TEST(FclAgreement, Cubicles)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/cubicles.cfg");
    compareWithFcl(cfg);
}
TEST(FclAgreement, Twistycool)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/Twistycool.cfg");
    compareWithFcl(cfg);
}
TEST(FclAgreement, MazePlanar)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "2D/Maze_planar.cfg");
    compareWithFcl(cfg);
}
TEST(FclAgreement, ProjectProblems) { compareWithFcl(test::sourcePath("problems/window_3d.cfg")); }
TEST(FclAgreement, Home)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/Home.cfg");
    compareWithFcl(cfg);
}
