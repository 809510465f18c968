// SPDX-License-Identifier: BSD-3-Clause
// ProofOdds: an optional proof is tried while it pays, on one query in kExploreEvery when it does
// not, and again on every query soon after it starts paying again; tallies are kept per checker
// and proof, for as many checkers as a scene of many bodies queries through one context.
#include "hybridcd/query/proof_odds.h"

#include <gtest/gtest.h>

#include <vector>

using namespace hcd;

namespace
{
/// Runs `queries` queries; the k-th try (counted from 0) succeeds when `succeeds(k)`. Returns how
/// many queries tried the proof.
template <class Succeeds>
int run(ProofOdds &odds, int queries, Succeeds succeeds)
{
    int tried = 0;
    for (int i = 0; i < queries; ++i)
        odds.attempt([&] { return succeeds(tried++); });
    return tried;
}

constexpr int kExplore = int(ProofOdds::kExploreEvery);
}  // namespace

TEST(ProofOdds, TriesEveryQueryWhileItPays)
{
    ProofOdds always;
    EXPECT_EQ(run(always, 500, [](int) { return true; }), 500);
    // One success in three tries is enough (the bar is one in kMinimumRate = 4).
    ProofOdds third;
    EXPECT_EQ(run(third, 500, [](int k) { return k % 3 == 0; }), 500);
}

TEST(ProofOdds, SkipsAProofThatSeldomPaysButStillSamplesIt)
{
    ProofOdds odds;
    // A fresh tally counts one success: three failures in a row close it, not the first.
    const int warmUp = run(odds, 64, [](int) { return false; });
    EXPECT_GE(warmUp, 4);
    EXPECT_LE(warmUp, 4 + 64 / kExplore);
    // Closed: one query in every kExploreEvery tries it, exactly.
    EXPECT_EQ(run(odds, 40 * kExplore, [](int) { return false; }), 40);
    // One success in eight tries does not keep it open: about one query in kExploreEvery tries it,
    // plus the few tries each success buys.
    ProofOdds rare;
    const int tried = run(rare, 4000, [](int k) { return k % 8 == 0; });
    EXPECT_LT(tried, 4000 / 4);
    EXPECT_GE(tried, 4000 / kExplore);
}

TEST(ProofOdds, ReopensSoonAfterTheProofPaysAgain)
{
    ProofOdds odds;
    run(odds, 1000, [](int) { return false; });
    // Successes from now on: within a bounded number of queries, every query is tried again.
    int firstOfTriedRun = -1, triedRun = 0;
    for (int query = 0; query < 20 * kExplore && triedRun < 50; ++query)
    {
        bool tried = false;
        odds.attempt([&] { return tried = true; });
        if (!tried)
            triedRun = 0;
        else if (triedRun++ == 0)
            firstOfTriedRun = query;
    }
    EXPECT_EQ(triedRun, 50);
    EXPECT_LE(firstOfTriedRun, 14 * kExplore);
}

TEST(ProofOdds, KeepsOneTallyPerCheckerAndProofForManyCheckers)
{
    ProofOddsByChecker table;
    // Forty checkers, as a scene of many bodies has one per pair of meshes, queried in turn through
    // one context: proof 0 always fails, proof 1 always succeeds. Each tally closes on its own and
    // none is lost to the others.
    std::vector<int> checkers(40);
    const int rounds = 20 * kExplore;
    std::vector<int> triedFailing(checkers.size(), 0), triedPaying(checkers.size(), 0);
    for (int round = 0; round < rounds; ++round)
        for (std::size_t c = 0; c < checkers.size(); ++c)
        {
            table.of(&checkers[c])[0].attempt([&] {
                ++triedFailing[c];
                return false;
            });
            table.of(&checkers[c])[1].attempt([&] {
                ++triedPaying[c];
                return true;
            });
        }
    for (std::size_t c = 0; c < checkers.size(); ++c)
    {
        EXPECT_EQ(triedPaying[c], rounds) << "checker " << c;
        EXPECT_LE(triedFailing[c], 4 + rounds / kExplore) << "checker " << c;
    }
}

TEST(ProofOdds, ATableOfManyCheckersStartsAfreshRatherThanGrowingWithoutBound)
{
    ProofOddsByChecker table;
    std::vector<int> checkers(ProofOddsByChecker::kMaxCheckers + 1);
    // The first checker's proof fails until its tally is closed: at most one try in 15 queries.
    run(table.of(&checkers[0])[0], 64, [](int) { return false; });
    EXPECT_LE(run(table.of(&checkers[0])[0], kExplore - 1, [](int) { return false; }), 1);
    // Every other checker once; the last one is one more than the table holds.
    for (std::size_t c = 1; c < checkers.size(); ++c)
        table.of(&checkers[c]);
    // The table started afresh: the first checker's tally is a fresh one, which tries again.
    EXPECT_GE(run(table.of(&checkers[0])[0], kExplore - 1, [](int) { return false; }), 3);
}
