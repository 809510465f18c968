// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/broadphase/sweep_and_prune.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace hcd
{
// ---------------------------------------------------------------------------------------------
// BodyPairSet

void BodyPairSet::grow()
{
    std::vector<std::uint64_t> old;
    old.swap(slots_);
    const std::size_t capacity = old.empty() ? 64 : 2 * old.size();
    slots_.assign(capacity, kEmpty);
    int bits = 0;
    while ((std::size_t(1) << bits) < capacity)
        ++bits;
    shift_ = 64 - bits;
    size_ = 0;
    for (const std::uint64_t k : old)
        if (k != kEmpty)
            insert(k);
}

bool BodyPairSet::insert(std::uint64_t key)
{
    if (2 * (size_ + 1) > slots_.size())
        grow();
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t s = slotOf(key);; s = (s + 1) & mask)
    {
        if (slots_[s] == key)
            return false;
        if (slots_[s] == kEmpty)
        {
            slots_[s] = key;
            ++size_;
            return true;
        }
    }
}

bool BodyPairSet::contains(std::uint64_t key) const
{
    if (size_ == 0)
        return false;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t s = slotOf(key);; s = (s + 1) & mask)
    {
        if (slots_[s] == key)
            return true;
        if (slots_[s] == kEmpty)
            return false;
    }
}

bool BodyPairSet::erase(std::uint64_t key)
{
    if (size_ == 0)
        return false;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t s = slotOf(key);; s = (s + 1) & mask)
    {
        if (slots_[s] == key)
        {
            eraseSlot(s);
            return true;
        }
        if (slots_[s] == kEmpty)
            return false;
    }
}

// Backward-shift deletion: the keys after the hole in its probe run move back into it when their
// home slot does not lie (cyclically) between the hole and their current slot.
void BodyPairSet::eraseSlot(std::size_t hole)
{
    const std::size_t mask = slots_.size() - 1;
    std::size_t s = hole;
    for (;;)
    {
        s = (s + 1) & mask;
        const std::uint64_t k = slots_[s];
        if (k == kEmpty)
            break;
        const std::size_t home = slotOf(k);
        // Distance from home to s versus from hole to s, both cyclic.
        if (((s - home) & mask) >= ((s - hole) & mask))
        {
            slots_[hole] = k;
            hole = s;
        }
    }
    slots_[hole] = kEmpty;
    --size_;
}

// ---------------------------------------------------------------------------------------------
// SweepAndPrune

namespace
{
// True when endpoint p sorts below q: by coordinate, and at the same coordinate a lower endpoint
// (tag bit 0 clear) below an upper one: closed intervals.
template <typename Endpoint>
bool below(const Endpoint &p, const Endpoint &q)
{
    return p.value < q.value || (p.value == q.value && (p.tag & 1u) < (q.tag & 1u));
}
}  // namespace

// The pair (a, b) starts to overlap on one axis: it is in the set exactly when the new boxes
// overlap on all three and the filters accept it.
void SweepAndPrune::pairStarts(std::uint32_t a, std::uint32_t b)
{
    const Body &x = bodies_[a];
    const Body &y = bodies_[b];
    if (x.filter.accepts(y.filter) && broadPhaseBoxesOverlap(x.box, y.box) && pairs_.insert(BodyPairSet::key(a, b)))
        ++pairsOf_[a], ++pairsOf_[b];
}

// The pair (a, b) is apart on one axis: out of the set. Most such events are of pairs that were
// never in it (apart on another axis), which the per-body counts rule out without a lookup.
void SweepAndPrune::pairEnds(std::uint32_t a, std::uint32_t b)
{
    if (pairsOf_[a] != 0 && pairsOf_[b] != 0 && pairs_.erase(BodyPairSet::key(a, b)))
        --pairsOf_[a], --pairsOf_[b];
}

// Moves the endpoint at `at` towards the front of its list while its predecessor sorts above it.
void SweepAndPrune::sortDown(int axis, std::uint32_t at)
{
    std::vector<Endpoint> &list = axes_[std::size_t(axis)];
    const Endpoint e = list[at];
    const std::uint32_t body = e.tag >> 1;
    const bool upper = (e.tag & 1u) != 0;
    while (at > 0)
    {
        const Endpoint &p = list[at - 1];
        if (!below(e, p))
            break;
        const std::uint32_t other = p.tag >> 1;
        if ((p.tag ^ e.tag) & 1u)
        {
            if (upper)  // our upper end passes below their lower end: apart on this axis
                pairEnds(body, other);
            else  // our lower end passes below their upper end: overlapping on this axis
                pairStarts(body, other);
        }
        list[at] = p;
        positions_[other][std::size_t(axis)][p.tag & 1u] = at;
        --at;
        ++swaps_;
    }
    list[at] = e;
    positions_[body][std::size_t(axis)][upper ? 1 : 0] = at;
}

// Moves the endpoint at `at` towards the back of its list while its successor sorts below it.
void SweepAndPrune::sortUp(int axis, std::uint32_t at)
{
    std::vector<Endpoint> &list = axes_[std::size_t(axis)];
    const Endpoint e = list[at];
    const std::uint32_t body = e.tag >> 1;
    const bool upper = (e.tag & 1u) != 0;
    const std::uint32_t last = std::uint32_t(list.size() - 1);
    while (at < last)
    {
        const Endpoint &n = list[at + 1];
        if (!below(n, e))
            break;
        const std::uint32_t other = n.tag >> 1;
        if ((n.tag ^ e.tag) & 1u)
        {
            if (upper)  // our upper end passes above their lower end: overlapping on this axis
                pairStarts(body, other);
            else  // our lower end passes above their upper end: apart on this axis
                pairEnds(body, other);
        }
        list[at] = n;
        positions_[other][std::size_t(axis)][n.tag & 1u] = at;
        ++at;
        ++swaps_;
    }
    list[at] = e;
    positions_[body][std::size_t(axis)][upper ? 1 : 0] = at;
}

BodyHandle SweepAndPrune::add(const BroadPhaseBox &box, std::uint32_t userData, BroadPhaseFilter filter)
{
    box.requireValid("SweepAndPrune::add");
    std::uint32_t index;
    if (!free_.empty())
    {
        index = free_.back();
        free_.pop_back();
    }
    else
    {
        if (bodies_.size() >= (std::size_t(1) << 31) - 1)
            throw std::length_error("SweepAndPrune::add: too many bodies");
        index = std::uint32_t(bodies_.size());
        bodies_.emplace_back();
        positions_.emplace_back();
        pairsOf_.push_back(0);
    }
    Body &b = bodies_[index];
    b.box = box;
    b.userData = userData;
    b.filter = filter;
    b.live = true;
    ++live_;
    // Both endpoints go to the end of every list (apart from every body on every axis), then sort
    // down into place: the lower one first, which the upper one behind it cannot block.
    for (int axis = 0; axis < 3; ++axis)
    {
        std::vector<Endpoint> &list = axes_[std::size_t(axis)];
        const std::uint32_t at = std::uint32_t(list.size());
        list.push_back({box.lower[axis], index << 1});
        list.push_back({box.upper[axis], (index << 1) | 1u});
        positions_[index][std::size_t(axis)] = {at, at + 1};
        sortDown(axis, at);
        sortDown(axis, positions_[index][std::size_t(axis)][1]);
    }
    return BodyHandle{index};
}

void SweepAndPrune::update(BodyHandle handle, const BroadPhaseBox &box)
{
    box.requireValid("SweepAndPrune::update");
    Body &b = bodies_[handle.index];
    const Position &position = positions_[handle.index];
    const BroadPhaseBox old = b.box;
    b.box = box;  // every event below tests the new boxes
    for (int axis = 0; axis < 3; ++axis)
    {
        const std::size_t k = std::size_t(axis);
        std::vector<Endpoint> &list = axes_[k];
        list[position[k][0]].value = box.lower[axis];
        list[position[k][1]].value = box.upper[axis];
        // Outward moves first (they cannot meet the body's other endpoint), then inward ones,
        // which stop at the other endpoint at the latest since lower sorts below upper.
        if (box.lower[axis] < old.lower[axis])
            sortDown(axis, position[k][0]);
        if (box.upper[axis] > old.upper[axis])
            sortUp(axis, position[k][1]);
        if (box.lower[axis] > old.lower[axis])
            sortUp(axis, position[k][0]);
        if (box.upper[axis] < old.upper[axis])
            sortDown(axis, position[k][1]);
    }
}

// One insertion-sort pass over a whole list with the events of sortDown, then every endpoint's
// position written again.
void SweepAndPrune::sortWholeAxis(int axis)
{
    std::vector<Endpoint> &list = axes_[std::size_t(axis)];
    const std::uint32_t n = std::uint32_t(list.size());
    for (std::uint32_t i = 1; i < n; ++i)
    {
        if (!below(list[i], list[i - 1]))
            continue;
        const Endpoint e = list[i];
        const std::uint32_t body = e.tag >> 1;
        const bool upper = (e.tag & 1u) != 0;
        std::uint32_t at = i;
        while (at > 0 && below(e, list[at - 1]))
        {
            const Endpoint &p = list[at - 1];
            if ((p.tag ^ e.tag) & 1u)
            {
                if (upper)
                    pairEnds(body, p.tag >> 1);
                else
                    pairStarts(body, p.tag >> 1);
            }
            list[at] = p;
            --at;
            ++swaps_;
        }
        list[at] = e;
    }
    for (std::uint32_t i = 0; i < n; ++i)
        positions_[list[i].tag >> 1][std::size_t(axis)][list[i].tag & 1u] = i;
}

void SweepAndPrune::updateMany(const BodyHandle *handles, const BroadPhaseBox *boxes, std::size_t count)
{
    if (16 * count < live_)
    {
        for (std::size_t i = 0; i < count; ++i)
            boxes[i].requireValid("SweepAndPrune::updateMany");
        for (std::size_t i = 0; i < count; ++i)
            update(handles[i], boxes[i]);
        return;
    }
    for (std::size_t i = 0; i < count; ++i)
        boxes[i].requireValid("SweepAndPrune::updateMany");
    // Every new box first (events test the new boxes), then each list sorted whole.
    for (std::size_t i = 0; i < count; ++i)
    {
        bodies_[handles[i].index].box = boxes[i];
        const Position &position = positions_[handles[i].index];
        for (std::size_t k = 0; k < 3; ++k)
        {
            axes_[k][position[k][0]].value = boxes[i].lower[int(k)];
            axes_[k][position[k][1]].value = boxes[i].upper[int(k)];
        }
    }
    for (int axis = 0; axis < 3; ++axis)
        sortWholeAxis(axis);
}

void SweepAndPrune::remove(BodyHandle handle)
{
    const std::uint32_t index = handle.index;
    Body &b = bodies_[index];
    pairs_.eraseBody(index, [&](std::uint32_t partner) { --pairsOf_[partner]; });
    pairsOf_[index] = 0;
    for (std::size_t k = 0; k < 3; ++k)
    {
        std::vector<Endpoint> &list = axes_[k];
        const std::uint32_t lo = positions_[index][k][0], hi = positions_[index][k][1];
        // Close both gaps: [lo+1, hi) moves back by one, (hi, end) by two.
        std::uint32_t to = lo;
        for (std::uint32_t from = lo + 1; from < std::uint32_t(list.size()); ++from)
        {
            if (from == hi)
                continue;
            list[to] = list[from];
            positions_[list[to].tag >> 1][k][list[to].tag & 1u] = to;
            ++to;
        }
        list.resize(list.size() - 2);
    }
    b.live = false;
    --live_;
    free_.push_back(index);
}

void SweepAndPrune::overlappingPairs(std::vector<UserDataPair> &out) const
{
    out.clear();
    out.reserve(pairs_.size());
    pairs_.forEach([&](std::uint64_t k) {
        const std::uint32_t a = bodies_[BodyPairSet::first(k)].userData;
        const std::uint32_t c = bodies_[BodyPairSet::second(k)].userData;
        out.emplace_back(std::min(a, c), std::max(a, c));
    });
    std::sort(out.begin(), out.end());
}

void SweepAndPrune::queryBox(const BroadPhaseBox &box, std::vector<std::uint32_t> &out, BroadPhaseFilter filter) const
{
    out.clear();
    if (!box.valid())
        return;  // a NaN query box overlaps nothing
    // Every body overlapping the box has its lower x end at or below box.upper.x: the front of
    // the x list up to there holds all candidates.
    for (const Endpoint &e : axes_[0])
    {
        if (e.value > box.upper.x())
            break;
        if (e.tag & 1u)
            continue;
        const Body &b = bodies_[e.tag >> 1];
        if (filter.accepts(b.filter) && broadPhaseBoxesOverlap(box, b.box))
            out.push_back(b.userData);
    }
    std::sort(out.begin(), out.end());
}

bool SweepAndPrune::validate() const
{
    for (std::size_t k = 0; k < 3; ++k)
    {
        const std::vector<Endpoint> &list = axes_[k];
        if (list.size() != 2 * live_)
            return false;
        for (std::size_t i = 0; i < list.size(); ++i)
        {
            if (i > 0 && below(list[i], list[i - 1]))
                return false;
            const Body &b = bodies_[list[i].tag >> 1];
            if (!b.live || positions_[list[i].tag >> 1][k][list[i].tag & 1u] != i)
                return false;
            const double expected = (list[i].tag & 1u) ? b.box.upper[int(k)] : b.box.lower[int(k)];
            if (!(list[i].value == expected))
                return false;
        }
    }
    std::size_t expectedPairs = 0;
    for (std::uint32_t i = 0; i < bodies_.size(); ++i)
        for (std::uint32_t j = i + 1; j < bodies_.size(); ++j)
        {
            const Body &a = bodies_[i], &b = bodies_[j];
            const bool reported =
                a.live && b.live && a.filter.accepts(b.filter) && broadPhaseBoxesOverlap(a.box, b.box);
            if (reported != pairs_.contains(BodyPairSet::key(i, j)))
                return false;
            expectedPairs += reported;
        }
    std::vector<std::uint32_t> counts(bodies_.size(), 0);
    pairs_.forEach([&](std::uint64_t k) { ++counts[BodyPairSet::first(k)], ++counts[BodyPairSet::second(k)]; });
    return expectedPairs == pairs_.size() && counts == pairsOf_;
}
}  // namespace hcd
