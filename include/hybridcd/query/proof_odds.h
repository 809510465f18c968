// SPDX-License-Identifier: BSD-3-Clause
// How often a cheap, optional proof has paid lately in one stream of queries: kept in the caller's
// QueryContext, it lets a checker skip a proof that seldom decides on this stream's poses.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hcd
{
/// Tries and successes of one proof in one stream. An optional proof (one that, when it fails,
/// leaves the answer to an exact test that follows) is worth trying while at least one try in
/// kMinimumRate succeeds, and once every kExploreEvery skips otherwise, so that a stream whose
/// poses change is noticed. A fresh tally counts one success, so a stream is not judged on its
/// first try; older tries weigh half once kWindow have been counted. Skipping a proof never changes
/// an answer, only its cost.
class ProofOdds
{
public:
    static constexpr std::uint32_t kMinimumRate = 4;
    static constexpr std::uint32_t kExploreEvery = 16;
    static constexpr std::uint32_t kWindow = 32;

    /// Whether to try the proof now (counts a skip when not).
    bool worthTrying()
    {
        if (hits_ * kMinimumRate >= tries_ || ++skipped_ >= kExploreEvery)
        {
            skipped_ = 0;
            return true;
        }
        return false;
    }
    /// Counts a try and whether it succeeded.
    void record(bool success)
    {
        ++tries_;
        hits_ += success ? 1u : 0u;
        if (tries_ >= kWindow)
        {
            tries_ /= 2;
            hits_ /= 2;
        }
    }

private:
    std::uint32_t tries_ = 1, hits_ = 1, skipped_ = 0;
};

/// One ProofOdds per checker (by address) and proof (a small number of the checker's choosing) in
/// a context: a context may serve several checkers.
class ProofOddsByChecker
{
public:
    ProofOdds &of(const void *checker, int proof = 0)
    {
        for (Entry &e : entries_)
            if (e.checker == checker && e.proof == proof)
                return e.odds;
        // A handful of checkers per context at most; beyond that the oldest entry is reused.
        if (entries_.size() < kEntries)
        {
            entries_.push_back({checker, proof, {}});
            return entries_.back().odds;
        }
        Entry &reused = entries_[next_++ % kEntries];
        reused = {checker, proof, {}};
        return reused.odds;
    }

private:
    static constexpr std::size_t kEntries = 16;
    struct Entry
    {
        const void *checker;
        int proof;
        ProofOdds odds;
    };
    std::vector<Entry> entries_;
    std::size_t next_ = 0;
};
}  // namespace hcd
