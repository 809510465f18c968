// SPDX-License-Identifier: BSD-3-Clause
// OMPL runs planners (and their checks) on many threads at once. Here 8 threads share one scene and
// one checker of each kind, and each asks every query hybridcd answers: state validity, motion
// validity with the last valid state, clearance (with a pushed-out valid state), and contacts. The
// answers must be bit-identical to a serial run. CI runs this test under ThreadSanitizer too.
#include "support/test_support.h"

#include "hybridcd/ompl/continuous_motion_validator.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/ompl/scene_planning.h"
#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/scene/problem_bodies.h"
#ifdef HYBRIDCD_HAVE_FCL
#include "hybridcd/fcl/fcl_checker.h"
#endif

#include <ompl/base/ScopedState.h>

#include <gtest/gtest.h>

#include <thread>

using namespace hcd;
namespace ob = ompl::base;

namespace
{
// Everything one state and one motion give; compared exactly (doubles bit for bit).
struct Answers
{
    bool valid = false;
    double clearance = 0.0;
    bool offered = false;
    std::size_t contacts = 0;
    bool motionFree = false;
    double lastValid = -1.0;

    bool operator==(const Answers &o) const
    {
        return valid == o.valid && clearance == o.clearance && offered == o.offered && contacts == o.contacts &&
               motionFree == o.motionFree && lastValid == o.lastValid;
    }
};

Answers ask(const PlanningProblem &planning, const ob::State *a, const ob::State *b, ob::State *scratch)
{
    const auto si = planning.setup->getSpaceInformation();
    Answers r;
    r.valid = planning.validity->isValid(a);
    double dist = 0.0;
    bool available = false;
    planning.validity->isValid(a, dist, scratch, available);
    r.clearance = dist;
    r.offered = available;
    r.contacts = planning.validity->checker().contacts(poseOfState(a, planning.planar), 64).size();
    std::pair<ob::State *, double> last{scratch, -1.0};
    r.motionFree = si->getMotionValidator()->checkMotion(a, b, last);
    r.lastValid = r.motionFree ? -1.0 : last.second;
    return r;
}

void storm(const CheckerCatalogue &catalogue, const std::string &checkerName)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    PlanningProblem planning = makePlanningProblem(problem, catalogue.make(checkerName, problem.scene));
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator()).setContactTolerance(1e-6);
    auto sampler = si->allocStateSampler();
    const std::size_t count = 48;
    std::vector<ob::State *> from(count), to(count);
    for (std::size_t i = 0; i < count; ++i)
    {
        from[i] = si->allocState();
        to[i] = si->allocState();
        sampler->sampleUniform(from[i]);
        sampler->sampleUniformNear(to[i], from[i], 0.15 * si->getMaximumExtent());
        si->enforceBounds(to[i]);
    }
    ob::State *serialScratch = si->allocState();
    std::vector<Answers> serial(count);
    for (std::size_t i = 0; i < count; ++i)
        serial[i] = ask(planning, from[i], to[i], serialScratch);
    si->freeState(serialScratch);

    const unsigned threads = 8;
    const std::size_t walked = test::kSanitizerCaseDivisor > 1 ? count / 2 : count;
    std::vector<std::vector<Answers>> parallel(threads, std::vector<Answers>(count));
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            ob::State *scratch = si->allocState();
            // Each thread walks the queries from its own offset, so different queries overlap in time;
            // under the sanitizers (each query 10-50x slower) half of them, still every query by
            // several threads at once.
            for (std::size_t k = 0; k < walked; ++k)
            {
                const std::size_t i = (k + 7 * t) % count;
                parallel[t][i] = ask(planning, from[i], to[i], scratch);
            }
            si->freeState(scratch);
        });
    for (auto &th : pool)
        th.join();
    for (unsigned t = 0; t < threads; ++t)
        for (std::size_t k = 0; k < walked; ++k)
        {
            const std::size_t i = (k + 7 * t) % count;
            ASSERT_TRUE(parallel[t][i] == serial[i]) << checkerName << ": thread " << t << " differs on query " << i;
        }
    std::size_t valid = 0, freeMotions = 0;
    for (std::size_t i = 0; i < count; ++i)
    {
        valid += serial[i].valid ? 1 : 0;
        freeMotions += serial[i].motionFree ? 1 : 0;
    }
    // Both outcomes present, or the storm exercises only one path.
    EXPECT_GT(valid, count / 10) << checkerName;
    EXPECT_LT(valid, count) << checkerName;
    EXPECT_GT(freeMotions, 0u) << checkerName;
    EXPECT_LT(freeMotions, count) << checkerName;
    for (std::size_t i = 0; i < count; ++i)
    {
        si->freeState(from[i]);
        si->freeState(to[i]);
    }
}
}  // namespace

TEST(Concurrency, EveryCheckerAnswersEveryQueryFromEightThreadsAsSerially)
{
#ifdef HYBRIDCD_HAVE_FCL
    const CheckerCatalogue catalogue = checkersWithFcl();
#else
    const CheckerCatalogue catalogue = CheckerCatalogue::builtIn();
#endif
    for (const std::string &name : catalogue.names())
    {
        SCOPED_TRACE(name);
        storm(catalogue, name);
    }
}

// A scene problem through its OMPL adapters: the validity checker, clearance and the continuous
// motion validator of all robots at once, shared by 8 threads (contexts from the checker's pool,
// the broad phase kept in each).
TEST(Concurrency, SceneAdaptersAnswerFromEightThreadsAsSerially)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/crossing_2d.cfg"));
    ScenePlanningProblem planning = makeScenePlanningProblem(problem, makeProblemScene(problem));
    const ob::SpaceInformationPtr si = planning.setup->getSpaceInformation();
    si->setup();
    const int count = test::cases(160);
    std::vector<ob::ScopedState<>> states;
    auto sampler = si->allocStateSampler();
    for (int i = 0; i < count + 1; ++i)
    {
        states.emplace_back(si->getStateSpace());
        sampler->sampleUniform(states.back().get());
    }
    auto answer = [&](int i) {
        Answers a;
        a.valid = planning.validity->isValid(states[std::size_t(i)].get());
        a.clearance = planning.validity->clearance(states[std::size_t(i)].get());
        ob::ScopedState<> last(si->getStateSpace());
        std::pair<ob::State *, double> lastValid{last.get(), -1.0};
        a.motionFree =
            planning.motion->checkMotion(states[std::size_t(i)].get(), states[std::size_t(i) + 1].get(), lastValid);
        a.lastValid = a.motionFree ? 1.0 : lastValid.second;
        return a;
    };
    std::vector<Answers> serial;
    int valid = 0;
    for (int i = 0; i < count; ++i)
    {
        serial.push_back(answer(i));
        valid += serial.back().valid ? 1 : 0;
    }
    EXPECT_GT(valid, 0);
    EXPECT_LT(valid, count);
    std::vector<std::vector<Answers>> parallel(8);
    std::vector<std::thread> threads;
    for (int t = 0; t < 8; ++t)
        threads.emplace_back([&, t] {
            for (int k = 0; k < count; ++k)
                parallel[std::size_t(t)].push_back(answer((k + 17 * t) % count));
        });
    for (std::thread &thread : threads)
        thread.join();
    for (int t = 0; t < 8; ++t)
        for (int k = 0; k < count; ++k)
        {
            // Verdicts exactly; distances and times up to rounding (GJK's warm start in a context
            // depends on what that context answered before).
            const Answers &p = parallel[std::size_t(t)][std::size_t(k)], &s = serial[std::size_t((k + 17 * t) % count)];
            ASSERT_EQ(p.valid, s.valid) << "thread " << t << ", state " << (k + 17 * t) % count;
            ASSERT_EQ(p.motionFree, s.motionFree) << "thread " << t << ", state " << (k + 17 * t) % count;
            ASSERT_NEAR(p.clearance, s.clearance, 1e-9 * (1.0 + std::abs(s.clearance)));
            ASSERT_NEAR(p.lastValid, s.lastValid, 1e-6);
        }
}
