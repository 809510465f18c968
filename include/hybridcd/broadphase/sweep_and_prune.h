// SPDX-License-Identifier: BSD-3-Clause
// Sweep and prune: the broad phase of the review (sections 1 and 3.4), incremental across queries.
//
// The idea. Two boxes overlap exactly when their intervals overlap on all three axes. Keep, per
// axis, the list of every body's two interval endpoints sorted by coordinate; the intervals that
// overlap on that axis are then the ones whose endpoints interleave. Bodies in motion planning and
// simulation move little between queries (coherence), so the lists stay almost sorted, and
// insertion sort puts them back in order in time proportional to the number of swaps, which is
// the number of interval endpoints that actually crossed (Baraff 1992; Cohen et al., I-COLLIDE).
//
// Ordering. Endpoints are ordered by coordinate and, at equal coordinates, every lower endpoint
// before every upper one. With that tie rule "lower_a before upper_b and lower_b before upper_a in
// the list" is exactly "lower_a <= upper_b and lower_b <= upper_a" on the doubles: closed
// intervals, so touching boxes overlap (broad_phase.h states the rule). Infinite coordinates need
// nothing special: -inf and +inf sort like any other value.
//
// Which pairs change. A pair's overlap on one axis changes only when a lower endpoint of one body
// and an upper endpoint of the other swap places, so the swaps of the insertion sort are exactly
// the events that can change the set of overlapping pairs. Three ways to keep that set were
// weighed:
//   - counts over three axes (per pair, on how many axes it overlaps; reported at three). Every
//     pair that overlaps on any one axis needs a counter: for N bodies spread in a cube that is
//     about N^2 / N^(1/3) entries, far more than the pairs reported, and all of them are touched
//     by the swaps;
//   - re-sweeping one chosen axis per query: O(N + pairs overlapping on that axis) every query, no
//     memory across queries, but no use of coherence for the pairs either, and one axis alone
//     overlaps for many more pairs than all three do;
//   - (chosen) a persistent set of the pairs overlapping on all three axes, changed only at swap
//     events: when a lower endpoint passes below an upper one (the pair starts to overlap on that
//     axis) the two boxes are tested on all three axes and the pair inserted if they overlap and
//     the filter accepts it; when an upper endpoint passes below a lower one the pair is erased
//     (its boxes are then apart on that axis). The set holds only reported pairs, and the work is
//     the swaps plus O(1) per swap.
// Why that is exact. Every update writes the body's new box first, then sorts the three lists.
// An event tests the new boxes, so it leaves the pair in the set exactly when it overlaps after
// the update (an erase event happens only when the new boxes are apart on the axis of the swap).
// A pair with no event on any axis kept the relative order of its endpoints on every axis, and the
// sorted order decides overlap, so its state did not change and neither did its membership. A new
// body's endpoints start at the end of every list (apart from every body, on every axis) and sort
// in from there; a removed body's pairs are erased with it.
//
// The proof does not need one body at a time: insertion sort swaps exactly the pairs of endpoints
// whose order changed, once each, so updateMany() writes every moved box first and then sorts
// each whole list in one pass, with the same events.
//
// Cost. update() is O(1 + swaps) expected; a jump across the scene costs O(N) swaps per axis,
// the price of a body that moved far. overlappingPairs() copies and sorts the set (O(P log P) for
// P pairs), so that its output is in a canonical order that matches the brute force's exactly.
// queryBox() walks the x list up to the query's upper x bound: O(bodies starting left of it).
#pragma once

#include "hybridcd/broadphase/broad_phase.h"
#include "hybridcd/broadphase/pair_set.h"

#include <array>
#include <cstdint>
#include <vector>

namespace hcd
{
/// Incremental sweep and prune over axis-aligned world-frame boxes (see the file comment). Bodies
/// are added, moved and removed by handle; the set of overlapping pairs (overlap rule and filter
/// of broad_phase.h) is kept up to date by every change and read by `overlappingPairs`. Not thread
/// safe: one writer, or many readers of an unchanging phase.
class SweepAndPrune
{
public:
    /// Adds a body with box `box` (world frame) and the caller's `userData` (reported in pairs;
    /// need not be unique). Throws std::invalid_argument when the box has a NaN bound or
    /// lower > upper. O(N) in the worst case (the new endpoints sort in from the end of the lists).
    BodyHandle add(const BroadPhaseBox &box, std::uint32_t userData,
                   BroadPhaseFilter filter = BroadPhaseFilter::dynamicBody());
    /// add() with the corners of `box` (BroadPhaseBox::of).
    BodyHandle add(const Aabb &box, std::uint32_t userData, BroadPhaseFilter filter = BroadPhaseFilter::dynamicBody())
    {
        return add(BroadPhaseBox::of(box), userData, filter);
    }

    /// Moves a body's box to `box`. Precondition: `body` was returned by add and not removed. Throws
    /// std::invalid_argument for an invalid box, leaving the phase unchanged. O(1 + endpoint swaps).
    void update(BodyHandle body, const BroadPhaseBox &box);
    void update(BodyHandle body, const Aabb &box) { update(body, BroadPhaseBox::of(box)); }

    /// Moves many bodies at once: the same result as update() on each in turn, but all boxes are
    /// written first and then each axis list is put in order by one insertion-sort pass over the
    /// whole list (O(N + swaps), walking memory in order), instead of one sort per endpoint that
    /// jumps around the body table. Taken when at least a sixteenth of the bodies move (every body
    /// of a simulation step, say); otherwise the bodies are updated one by one. Preconditions as
    /// for update(); every box is checked before anything changes (std::invalid_argument).
    void updateMany(const BodyHandle *bodies, const BroadPhaseBox *boxes, std::size_t count);

    /// Removes a body and its pairs. Precondition: `body` is live. O(N + capacity of the pair set).
    void remove(BodyHandle body);

    /// Number of live bodies.
    std::size_t size() const { return live_; }
    /// Number of overlapping, filter-accepted pairs (what overlappingPairs reports).
    std::size_t pairCount() const { return pairs_.size(); }
    /// The box a live body was last given.
    const BroadPhaseBox &box(BodyHandle body) const { return bodies_[body.index].box; }
    /// The user data of a live body.
    std::uint32_t userData(BodyHandle body) const { return bodies_[body.index].userData; }

    /// Replaces `out` with every overlapping pair of live bodies that the filters accept, as
    /// (min, max) of the two bodies' user data, sorted lexicographically.
    void overlappingPairs(std::vector<UserDataPair> &out) const;

    /// Replaces `out` with the user data of every live body whose box overlaps `box` (closed, as
    /// between bodies) and whose filter `filter` accepts, sorted ascending.
    void queryBox(const BroadPhaseBox &box, std::vector<std::uint32_t> &out,
                  BroadPhaseFilter filter = BroadPhaseFilter::everything()) const;
    void queryBox(const Aabb &box, std::vector<std::uint32_t> &out,
                  BroadPhaseFilter filter = BroadPhaseFilter::everything()) const
    {
        queryBox(BroadPhaseBox::of(box), out, filter);
    }

    /// Endpoint swaps done by updates and adds so far (a measure of the work coherence saved).
    std::uint64_t swaps() const { return swaps_; }
    void resetSwaps() { swaps_ = 0; }

    /// Checks the internal invariants (sorted lists, endpoint positions, the pair set equal to a
    /// recomputation); O(N^2). For tests.
    bool validate() const;

private:
    // An endpoint: its coordinate and (body index << 1) | (1 for the upper endpoint).
    struct Endpoint
    {
        double value;
        std::uint32_t tag;
    };
    // What an event reads, in one 64-byte record per body; the endpoint positions, which every
    // swap writes, are kept apart in `positions_`.
    struct Body
    {
        BroadPhaseBox box;
        std::uint32_t userData = 0;
        BroadPhaseFilter filter;
        bool live = false;
    };
    // Index of a body's lower and upper endpoint in each axis list.
    using Position = std::array<std::array<std::uint32_t, 2>, 3>;

    void sortDown(int axis, std::uint32_t at);
    void sortUp(int axis, std::uint32_t at);
    void pairStarts(std::uint32_t a, std::uint32_t b);
    void pairEnds(std::uint32_t a, std::uint32_t b);
    void sortWholeAxis(int axis);

    std::vector<Body> bodies_;
    std::vector<Position> positions_;
    std::vector<std::uint32_t> pairsOf_;  // number of pairs in the set per body
    std::vector<std::uint32_t> free_;
    std::array<std::vector<Endpoint>, 3> axes_;
    BodyPairSet pairs_;
    std::size_t live_ = 0;
    std::uint64_t swaps_ = 0;
};
}  // namespace hcd
