// SPDX-License-Identifier: BSD-3-Clause
// The reference broad phase: every pair of bodies tested on every query, O(N^2), with the same
// interface, overlap rule and filter as the sweep and prune (broad_phase.h), against which the
// latter is tested pair for pair (as Jolt keeps BroadPhaseBruteForce and Coal its naive manager).
#pragma once

#include "hybridcd/broadphase/broad_phase.h"

#include <cstdint>
#include <vector>

namespace hcd
{
/// All pairs, all the time: a table of bodies and nothing else. The interface is SweepAndPrune's.
class BruteForceBroadPhase
{
public:
    /// Adds a body (world-frame box, user data, filter). Throws std::invalid_argument when the box
    /// has a NaN bound or lower > upper. O(1).
    BodyHandle add(const BroadPhaseBox &box, std::uint32_t userData,
                   BroadPhaseFilter filter = BroadPhaseFilter::dynamicBody());
    BodyHandle add(const Aabb &box, std::uint32_t userData, BroadPhaseFilter filter = BroadPhaseFilter::dynamicBody())
    {
        return add(BroadPhaseBox::of(box), userData, filter);
    }
    /// Moves a live body's box (throws std::invalid_argument for an invalid box). O(1).
    void update(BodyHandle body, const BroadPhaseBox &box);
    void update(BodyHandle body, const Aabb &box) { update(body, BroadPhaseBox::of(box)); }
    /// Removes a live body. O(1).
    void remove(BodyHandle body);

    std::size_t size() const { return live_; }

    /// Every overlapping pair the filters accept as (min, max) user data, sorted. O(N^2).
    void overlappingPairs(std::vector<UserDataPair> &out) const;
    /// The user data of every body overlapping `box` that `filter` accepts, sorted. O(N).
    void queryBox(const BroadPhaseBox &box, std::vector<std::uint32_t> &out,
                  BroadPhaseFilter filter = BroadPhaseFilter::everything()) const;
    void queryBox(const Aabb &box, std::vector<std::uint32_t> &out,
                  BroadPhaseFilter filter = BroadPhaseFilter::everything()) const
    {
        queryBox(BroadPhaseBox::of(box), out, filter);
    }

private:
    struct Body
    {
        BroadPhaseBox box;
        std::uint32_t userData = 0;
        BroadPhaseFilter filter;
        bool live = false;
    };
    std::vector<Body> bodies_;
    std::vector<std::uint32_t> free_;
    std::size_t live_ = 0;
};
}  // namespace hcd
