// SPDX-License-Identifier: BSD-3-Clause
// ProofOdds: an optional proof is tried while it pays, now and then when it does not, and again
// on every query soon after it starts paying again; tallies are kept per checker.
#include "hybridcd/query/proof_odds.h"

#include <gtest/gtest.h>

#include <cstdint>

using namespace hcd;

namespace
{
/// Runs `queries` queries whose proof succeeds when `succeeds(i)`, returning how many were tried.
template <class Succeeds>
int run(ProofOdds &odds, int queries, Succeeds succeeds)
{
    int tried = 0;
    for (int i = 0; i < queries; ++i)
        if (odds.worthTrying())
        {
            ++tried;
            odds.record(succeeds(i));
        }
    return tried;
}
}  // namespace

TEST(ProofOdds, TriesEveryQueryWhileItPays)
{
    ProofOdds always;
    EXPECT_EQ(run(always, 500, [](int) { return true; }), 500);
    // One success in three tries is enough (the bar is one in kMinimumRate = 4).
    ProofOdds third;
    EXPECT_EQ(run(third, 500, [](int i) { return i % 3 == 0; }), 500);
}

TEST(ProofOdds, SkipsAProofThatSeldomPaysButStillSamplesIt)
{
    ProofOdds odds;
    // A fresh tally tries; after a run of failures the gate closes.
    const int warmUp = run(odds, 64, [](int) { return false; });
    EXPECT_GE(warmUp, 2);
    EXPECT_LT(warmUp, 64);
    // Closed: one try in every kExploreEvery queries, exactly.
    const int queries = 40 * int(ProofOdds::kExploreEvery);
    EXPECT_EQ(run(odds, queries, [](int) { return false; }), 40);
    // One success in eight tries does not reopen it.
    ProofOdds rare;
    const int tried = run(rare, 4000, [](int i) { return i % 8 == 0; });
    EXPECT_LT(tried, 4000 / 2);
}

TEST(ProofOdds, ReopensSoonAfterTheProofPaysAgain)
{
    ProofOdds odds;
    run(odds, 1000, [](int) { return false; });
    // Successes from now on: within a bounded number of queries, every query is tried again.
    int query = 0;
    int firstOfTriedRun = -1, triedRun = 0;
    for (; query < 20 * int(ProofOdds::kExploreEvery) && triedRun < 50; ++query)
    {
        if (odds.worthTrying())
        {
            odds.record(true);
            if (triedRun++ == 0)
                firstOfTriedRun = query;
        }
        else
            triedRun = 0;
    }
    EXPECT_EQ(triedRun, 50);
    EXPECT_LE(firstOfTriedRun, 14 * int(ProofOdds::kExploreEvery));
}

TEST(ProofOdds, KeepsOneTallyPerChecker)
{
    ProofOddsByChecker byChecker;
    int a = 0, b = 0;
    ProofOdds &failing = byChecker.of(&a);
    run(failing, 500, [](int) { return false; });
    // Another checker in the same context starts fresh and keeps its own tally.
    EXPECT_EQ(run(byChecker.of(&b), 100, [](int) { return true; }), 100);
    EXPECT_LT(run(byChecker.of(&a), 100, [](int) { return false; }), 100 / 4);
    // Beyond a handful of checkers, entries are reused, and a reused one starts fresh.
    int many[20];
    for (int &m : many)
        EXPECT_EQ(run(byChecker.of(&m), 10, [](int) { return true; }), 10);
    EXPECT_EQ(&byChecker.of(&many[19]), &byChecker.of(&many[19]));
}
