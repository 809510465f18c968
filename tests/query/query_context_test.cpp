// SPDX-License-Identifier: BSD-3-Clause
// Caller-owned query contexts: one context reused across queries, poses and checkers gives the
// answers of a fresh context per query; the pool lends distinct contexts to concurrent borrowers
// and reuses returned ones.
#include "support/test_support.h"

#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/query/query_context_pool.h"
#include "hybridcd/query/traversal_stack.h"

#include <gtest/gtest.h>

#include <iostream>
#include <set>
#include <thread>

using namespace hcd;

namespace
{
LoadedProblem windowProblem() { return loadProblem(test::sourcePath("problems/window_3d.cfg")); }
}  // namespace

// One context, interleaved over several checkers (different volume types share nothing, the same
// type shares the placed-robot scratch) and every kind of query, against a fresh context each.
TEST(QueryContext, OneContextAcrossCheckersAndQueriesGivesTheOneOffAnswers)
{
    const LoadedProblem problem = windowProblem();
    test::TestRandom rng(test::seeded(41));
    const std::vector<RigidTransform> poses =
        problem.config.planar ? std::vector<RigidTransform>{} : test::randomPoses(problem, 120, rng);
    ASSERT_FALSE(poses.empty());
    std::vector<std::unique_ptr<CollisionChecker>> checkers;
    for (const char *name : {"obb", "ellipsoid", "lp", "bruteforce"})
        checkers.push_back(makeChecker(name, problem.scene));
    // A second obb checker on the same scene: same scratch type, another tree object.
    checkers.push_back(makeChecker("obb", problem.scene, ContactSemantics::SurfaceOnly));

    QueryContext shared;
    std::size_t colliding = 0, queries = 0;
    for (const RigidTransform &pose : poses)
        for (const auto &checker : checkers)
        {
            SCOPED_TRACE(checker->name());
            const bool hit = checker->collides(pose, shared);
            EXPECT_EQ(hit, checker->collides(pose));
            colliding += hit ? 1 : 0;
            EXPECT_EQ(checker->withinDistance(pose, 0.05, shared), checker->withinDistance(pose, 0.05));
            EXPECT_EQ(checker->withinSweptDistance(pose, 0.01, 0.02, 1.0, shared),
                      checker->withinSweptDistance(pose, 0.01, 0.02, 1.0));
            EXPECT_EQ(checker->contacts(pose, 4, shared).size(), checker->contacts(pose, 4).size());
            if (checker->name() != "bruteforce")
                EXPECT_EQ(checker->distance(pose, shared), checker->distance(pose));
            ++queries;
        }
    EXPECT_GT(colliding, 0u);
    EXPECT_LT(colliding, queries);
    EXPECT_GT(shared.stats.primitiveTests + shared.stats.boundingVolumeTests, 0u);
}

// A fresh context's counters are what the one-off form reports through QueryStats.
TEST(QueryContext, CountersMatchTheOneOffStats)
{
    const LoadedProblem problem = windowProblem();
    const auto checker = makeChecker("obb", problem.scene);
    test::TestRandom rng(test::seeded(42));
    QueryStats fresh, oneOff;
    for (const RigidTransform &pose : test::randomPoses(problem, 50, rng))
    {
        QueryContext context;
        checker->collides(pose, context);
        fresh.boundingVolumeTests += context.stats.boundingVolumeTests;
        fresh.primitiveTests += context.stats.primitiveTests;
        checker->collides(pose, &oneOff);
    }
    EXPECT_EQ(fresh.boundingVolumeTests, oneOff.boundingVolumeTests);
    EXPECT_EQ(fresh.primitiveTests, oneOff.primitiveTests);
    EXPECT_GT(oneOff.boundingVolumeTests, 0u);
}

// Coherence: the pair that decided the last "yes" is tried first. Along a motion that ends in
// contact, the states after the first contact mostly collide at the same pair, so a context that
// carries it over does far fewer volume tests, with the same answers as fresh contexts.
TEST(QueryContext, TheLastContactPairIsTriedFirst)
{
    const LoadedProblem problem = windowProblem();
    const auto checker = makeChecker("obb", problem.scene, ContactSemantics::SurfaceOnly);
    const auto reference = makeChecker("bruteforce", problem.scene, ContactSemantics::SurfaceOnly);
    test::TestRandom rng(test::seeded(44));
    std::size_t colliding = 0;
    std::uint64_t carried = 0, fresh = 0;
    QueryContext context;
    for (const RigidTransform &a : test::randomPoses(problem, 40, rng))
    {
        // A short straight motion from each random pose, 50 states, same orientation.
        const Vec3 step = Vec3(0.02, -0.01, 0.015);
        for (int k = 0; k < 50; ++k)
        {
            RigidTransform pose = a;
            pose.translation += double(k) * step;
            const std::uint64_t before = context.stats.boundingVolumeTests;
            const bool hit = checker->collides(pose, context);
            carried += context.stats.boundingVolumeTests - before;
            QueryContext once;
            EXPECT_EQ(checker->collides(pose, once), hit);
            fresh += once.stats.boundingVolumeTests;
            EXPECT_EQ(hit, reference->collides(pose));
            colliding += hit ? 1 : 0;
        }
    }
    EXPECT_GT(colliding, 200u);
    EXPECT_LT(carried, fresh);
    std::cout << "[ coherence ] " << colliding << " colliding of 2000 states; volume tests " << carried
              << " with the last pair carried over, " << fresh << " without\n";
}

TEST(QueryContextPool, LendsDistinctContextsAndReusesReturnedOnes)
{
    QueryContextPool pool;
    QueryContext *first = nullptr;
    {
        const QueryContextPool::Lease a = pool.borrow();
        const QueryContextPool::Lease b = pool.borrow();
        EXPECT_NE(&*a, &*b);  // both in use at once
        first = &*a;
    }
    // Returned contexts come back (either one; both were returned).
    const QueryContextPool::Lease c = pool.borrow();
    const QueryContextPool::Lease d = pool.borrow();
    const std::set<QueryContext *> reused{&*c, &*d};
    EXPECT_EQ(reused.size(), 2u);
    EXPECT_EQ(reused.count(first), 1u);
}

// More borrowers at once than the pool keeps idle: each still gets a context of its own.
TEST(QueryContextPool, ManyThreadsBorrowAtOnce)
{
    const LoadedProblem problem = windowProblem();
    const auto checker = makeChecker("obb", problem.scene);
    test::TestRandom rng(test::seeded(43));
    const std::vector<RigidTransform> poses = test::randomPoses(problem, 64, rng);
    std::vector<char> expected;
    for (const RigidTransform &p : poses)
        expected.push_back(checker->collides(p));

    QueryContextPool pool;
    std::vector<std::thread> threads;
    std::vector<int> mismatches(8, 0);
    for (int t = 0; t < 8; ++t)
        threads.emplace_back([&, t] {
            for (int round = 0; round < 20; ++round)
                for (std::size_t i = 0; i < poses.size(); ++i)
                {
                    const QueryContextPool::Lease context = pool.borrow();
                    mismatches[std::size_t(t)] += checker->collides(poses[i], *context) != bool(expected[i]);
                }
        });
    for (std::thread &t : threads)
        t.join();
    for (int m : mismatches)
        EXPECT_EQ(m, 0);
}

TEST(NearestPairQueue, PopsInTheOrderOfASortAcrossInterleavedPushesAndPops)
{
    // Brute force: a sorted list. Ties, repeated values and an emptied queue included.
    test::TestRandom rng(test::seeded(21));
    std::uniform_int_distribution<int> value(0, 40), action(0, 2);
    NearestPairQueue queue;
    for (int round = 0; round < 200; ++round)
    {
        queue.clear();
        std::multiset<double> reference;
        for (int step = 0; step < 300; ++step)
        {
            if (action(rng) > 0 || reference.empty())
            {
                const double bound = 0.25 * value(rng);
                queue.push({{std::uint32_t(step), std::uint32_t(round)}, bound});
                reference.insert(bound);
            }
            else
            {
                ASSERT_EQ(queue.nearestBound(), *reference.begin());
                ASSERT_EQ(queue.pop().bound, *reference.begin());
                reference.erase(reference.begin());
            }
            ASSERT_EQ(queue.empty(), reference.empty());
        }
        while (!reference.empty())
        {
            ASSERT_EQ(queue.pop().bound, *reference.begin());
            reference.erase(reference.begin());
        }
        EXPECT_TRUE(queue.empty());
    }
}
