// SPDX-License-Identifier: BSD-3-Clause
// FCL, set up as OMPL.app sets it up, against the brute-force reference on the same poses.
#include "support/test_support.h"

#include "hybridcd/fcl/fcl_checker.h"
#include "hybridcd/query/checker_registry.h"

#include <gtest/gtest.h>

using namespace hcd;

namespace
{
void compareWithFcl(const std::string &cfg)
{
    registerFclChecker();
    const LoadedProblem problem = loadProblem(cfg);
    test::TestRandom rng(99);
    const auto poses = test::randomPoses(problem, 3000, rng);
    const auto fcl = makeChecker("fcl", problem.scene);
    const auto reference = makeChecker("bruteforce", problem.scene);
    std::size_t colliding = 0, fclMissed = 0, fclExtra = 0;
    for (const RigidTransform &pose : poses)
    {
        const bool expected = reference->collides(pose), got = fcl->collides(pose);
        colliding += expected;
        fclMissed += expected && !got;
        fclExtra += !expected && got;
    }
    // Both treat meshes as surfaces; on random (never exactly touching) poses they must agree.
    // Containment (robot inside a closed obstacle) is free for both here: it only differs once
    // solid semantics are asked for, and is counted by the solid-object tests.
    EXPECT_EQ(fclMissed, 0u) << cfg;
    EXPECT_EQ(fclExtra, 0u) << cfg;
    EXPECT_GT(colliding, poses.size() / 10);
    EXPECT_LT(colliding, poses.size() * 9 / 10);
}
}  // namespace

TEST(FclAgreement, Cubicles) { HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/cubicles.cfg"); compareWithFcl(cfg); }
TEST(FclAgreement, Twistycool) { HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/Twistycool.cfg"); compareWithFcl(cfg); }
TEST(FclAgreement, MazePlanar) { HYBRIDCD_REQUIRE_OMPLAPP(cfg, "2D/Maze_planar.cfg"); compareWithFcl(cfg); }
TEST(FclAgreement, ProjectProblems) { compareWithFcl(test::sourcePath("problems/window_3d.cfg")); }
