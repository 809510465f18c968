// SPDX-License-Identifier: BSD-3-Clause
// The retraction sampler against brute force: every sample it retracts is valid (bounds, and the
// brute-force checker finds no contact) and lies near an obstacle (its clearance below the robot's
// radius), and the share of valid samples rises above uniform sampling.
#include "support/test_support.h"

#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/ompl/retraction_sampler.h"
#include "hybridcd/query/checker_catalogue.h"

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <gtest/gtest.h>

using namespace hcd;
namespace ob = ompl::base;

namespace
{
void expectRetractedSamplesValid(const std::string &cfg, int samples)
{
    const LoadedProblem problem = loadProblem(cfg);
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene));
    const auto si = planning.setup->getSpaceInformation();
    const auto reference = makeChecker("bruteforce", problem.scene);
    const double radius = problem.robot.mesh->radiusAboutOrigin();

    // Uniform first, then retraction (OMPL's generator is seeded before every test).
    ob::StateSamplerPtr uniform = si->allocStateSampler();
    RetractionStateSampler retraction(si->getStateSpace().get(), planning.validity);
    ob::State *s = si->allocState();
    int uniformValid = 0, retractionValid = 0;
    for (int i = 0; i < samples; ++i)
    {
        uniform->sampleUniform(s);
        uniformValid += si->isValid(s);
    }
    std::uint64_t retracted = 0;
    for (int i = 0; i < samples; ++i)
    {
        retraction.sampleUniform(s);
        const RigidTransform pose = poseOfState(s, problem.config.planar);
        const bool valid = si->satisfiesBounds(s) && !reference->collides(pose);
        retractionValid += valid;
        if (retraction.retracted() > retracted)  // this sample was pushed out
        {
            retracted = retraction.retracted();
            ASSERT_TRUE(valid) << cfg << " sample " << i;
            EXPECT_LT(reference->distance(pose), radius) << cfg << " sample " << i;
        }
    }
    EXPECT_EQ(retraction.drawn(), std::uint64_t(samples));
    EXPECT_GT(retracted, 0u) << cfg;
    EXPECT_GT(retractionValid, uniformValid) << cfg;
    EXPECT_GE(std::uint64_t(retractionValid), retracted) << cfg;
    si->freeState(s);
}
}  // namespace

TEST(RetractionSampler, RetractedSamplesAreValidAndNearObstacles)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cubicles, "3D/cubicles.cfg");
    expectRetractedSamplesValid(cubicles, test::cases(300));
    HYBRIDCD_REQUIRE_OMPLAPP(maze, "2D/Maze_planar.cfg");
    expectRetractedSamplesValid(maze, test::cases(300));
    expectRetractedSamplesValid(test::sourcePath("problems/window_3d.cfg"), test::cases(300));
}
