// SPDX-License-Identifier: BSD-3-Clause
#include "support/test_support.h"

#include "hybridcd/io/path_file.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/query/checker_catalogue.h"

#include <ompl/base/spaces/SE3StateSpace.h>

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

using namespace hcd;

TEST(ValidityChecker, ConcurrentQueriesMatchSerialOnes)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene));
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    auto sampler = si->allocStateSampler();
    std::vector<ompl::base::State *> states(4000);
    for (auto &s : states)
    {
        s = si->allocState();
        sampler->sampleUniform(s);
    }
    std::vector<char> serial(states.size());
    for (std::size_t i = 0; i < states.size(); ++i)
        serial[i] = planning.validity->isValid(states[i]);
    planning.validity->resetCounters();

    const unsigned threads = 8;
    std::vector<std::vector<char>> parallel(threads, std::vector<char>(states.size()));
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            for (std::size_t i = 0; i < states.size(); ++i)
                parallel[t][i] = planning.validity->isValid(states[(i + 97 * t) % states.size()]) ? 1 : 0;
        });
    for (auto &th : pool)
        th.join();
    for (unsigned t = 0; t < threads; ++t)
        for (std::size_t i = 0; i < states.size(); ++i)
            ASSERT_EQ(parallel[t][i], serial[(i + 97 * t) % states.size()]);
    // The atomic counters saw every query exactly once.
    EXPECT_EQ(planning.validity->checkCount(), threads * states.size());
    std::size_t valid = std::count(serial.begin(), serial.end(), 1);
    EXPECT_GT(valid, states.size() / 10);
    EXPECT_LT(valid, states.size() * 9 / 10);
    for (auto *s : states)
        si->freeState(s);
}

TEST(ValidityChecker, BoundsAreAppliedAndPosesFollowOmplAppConventions)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene));
    planning.setup->setup();
    const auto &pdef = planning.setup->getProblemDefinition();
    EXPECT_TRUE(planning.validity->isValid(pdef->getStartState(0)));
    ompl::base::ScopedState<ompl::base::SE3StateSpace> s(planning.setup->getStateSpace());
    s = pdef->getStartState(0);
    s->setX(1e6);  // far outside the volume, and outside every obstacle
    EXPECT_TRUE(planning.validity->collisionFree(s.get()));
    EXPECT_FALSE(planning.validity->isValid(s.get()));
    // The state's pose is exactly the .path convention: x y z then quaternion x y z w.
    const auto values = stateToPoseValues(s.get(), false);
    ASSERT_EQ(values.size(), 7u);
    EXPECT_EQ(values[0], 1e6);
    EXPECT_EQ(values[6], s->rotation().w);
}

// A free pose a rounding step from contact (found by a held-out probe): its distance rounds to 0.
// The clearance is then +0, and isValid with a distance agrees with isValid without one: the
// collision check decides.
TEST(ValidityChecker, AFreePoseWhoseDistanceRoundsToZeroIsValidWithClearanceZero)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("tests/hostile/free_zero.cfg"));
    const std::vector<PoseRecord> poses = readPoses(test::sourcePath("tests/hostile/free_zero.path"), false);
    ASSERT_EQ(poses.size(), 1u);
    for (const char *name : {"bruteforce", "obb", "auto"})
    {
        PlanningProblem planning = makePlanningProblem(problem, makeChecker(name, problem.scene));
        planning.setup->setup();
        ompl::base::ScopedState<ompl::base::SE3StateSpace> s(planning.setup->getStateSpace());
        s->setXYZ(poses[0].values[0], poses[0].values[1], poses[0].values[2]);
        s->rotation().x = poses[0].values[3];
        s->rotation().y = poses[0].values[4];
        s->rotation().z = poses[0].values[5];
        s->rotation().w = poses[0].values[6];
        EXPECT_TRUE(planning.validity->collisionFree(s.get())) << name;
        const double clearance = planning.validity->clearance(s.get());
        EXPECT_EQ(clearance, 0.0) << name;
        EXPECT_FALSE(std::signbit(clearance)) << name;
        double dist = -1.0;
        EXPECT_TRUE(planning.validity->isValid(s.get())) << name;
        EXPECT_TRUE(planning.validity->isValid(s.get(), dist)) << name;
        EXPECT_EQ(dist, 0.0) << name;
    }
}
