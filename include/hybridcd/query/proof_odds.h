// SPDX-License-Identifier: BSD-3-Clause
// How often a cheap, optional proof has paid lately in one stream of queries: kept in the caller's
// QueryContext, it lets a checker skip a proof that seldom decides on this stream's poses.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>

namespace hcd
{
/// Tries and successes of one proof in one stream. An optional proof (one that, when it fails,
/// leaves the answer to an exact test that follows) is worth trying while at least one try in
/// kMinimumRate succeeds; otherwise it is tried on one query in kExploreEvery, so that a stream
/// whose poses change is noticed. A fresh tally counts one success, so a stream is not judged on
/// its first try; older tries weigh half once kWindow have been counted. Skipping a proof never
/// changes an answer, only its cost.
class ProofOdds
{
public:
    static constexpr std::uint32_t kMinimumRate = 4;
    static constexpr std::uint32_t kExploreEvery = 16;
    static constexpr std::uint32_t kWindow = 32;

    /// Runs `proof` (a callable returning whether it succeeded) when it is worth trying now, and
    /// counts the outcome; false when skipped, which proves nothing.
    template <class Proof>
    bool attempt(Proof &&proof)
    {
        if (!tryNow())
            return false;
        const bool success = proof();
        record(success);
        return success;
    }

private:
    /// Whether this query tries the proof (a query that does not counts towards the next sample).
    bool tryNow()
    {
        if (hits_ * kMinimumRate >= tries_ || ++skipped_ >= kExploreEvery)
        {
            skipped_ = 0;
            return true;
        }
        return false;
    }
    /// Counts a try and whether it succeeded; older tries weigh half once kWindow have been counted.
    void record(bool success)
    {
        ++tries_;
        hits_ += success ? 1u : 0u;
        if (tries_ >= kWindow)
        {
            tries_ /= 2;
            hits_ = (hits_ + 1) / 2;  // rounded up: one recent success is not lost
        }
    }

    std::uint32_t tries_ = 1, hits_ = 1, skipped_ = 0;
};

/// The tallies of one context, per checker (by address), one per proof (an index below kProofs of
/// the checker's choosing). A scene of many bodies queries one checker per pair of meshes through
/// one context, so the table holds them all; it starts afresh beyond kMaxCheckers (a context that
/// outlives many checkers), which only costs the tallies.
class ProofOddsByChecker
{
public:
    static constexpr std::size_t kProofs = 2;
    static constexpr std::size_t kMaxCheckers = 4096;
    using Tallies = std::array<ProofOdds, kProofs>;

    Tallies &of(const void *checker)
    {
        // Most streams query one checker: its tallies are kept at hand (map nodes do not move).
        if (checker != last_ || !lastTallies_)
        {
            if (tallies_.size() >= kMaxCheckers && tallies_.find(checker) == tallies_.end())
                tallies_.clear();
            lastTallies_ = &tallies_[checker];
            last_ = checker;
        }
        return *lastTallies_;
    }

private:
    std::unordered_map<const void *, Tallies> tallies_;
    const void *last_ = nullptr;
    Tallies *lastTallies_ = nullptr;
};
}  // namespace hcd
