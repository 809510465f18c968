// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/broadphase/brute_force_broad_phase.h"

#include <algorithm>

namespace hcd
{
BodyHandle BruteForceBroadPhase::add(const BroadPhaseBox &box, std::uint32_t userData, BroadPhaseFilter filter)
{
    box.requireValid("BruteForceBroadPhase::add");
    std::uint32_t index;
    if (!free_.empty())
    {
        index = free_.back();
        free_.pop_back();
    }
    else
    {
        index = std::uint32_t(bodies_.size());
        bodies_.emplace_back();
    }
    bodies_[index] = Body{box, userData, filter, true};
    ++live_;
    return BodyHandle{index};
}

void BruteForceBroadPhase::update(BodyHandle body, const BroadPhaseBox &box)
{
    box.requireValid("BruteForceBroadPhase::update");
    bodies_[body.index].box = box;
}

void BruteForceBroadPhase::remove(BodyHandle body)
{
    bodies_[body.index].live = false;
    --live_;
    free_.push_back(body.index);
}

void BruteForceBroadPhase::overlappingPairs(std::vector<UserDataPair> &out) const
{
    out.clear();
    for (std::size_t i = 0; i < bodies_.size(); ++i)
    {
        const Body &a = bodies_[i];
        if (!a.live)
            continue;
        for (std::size_t j = i + 1; j < bodies_.size(); ++j)
        {
            const Body &b = bodies_[j];
            if (b.live && a.filter.accepts(b.filter) && broadPhaseBoxesOverlap(a.box, b.box))
                out.emplace_back(std::min(a.userData, b.userData), std::max(a.userData, b.userData));
        }
    }
    std::sort(out.begin(), out.end());
}

void BruteForceBroadPhase::queryBox(const BroadPhaseBox &box, std::vector<std::uint32_t> &out,
                                    BroadPhaseFilter filter) const
{
    out.clear();
    if (!box.valid())
        return;  // as the sweep and prune: an invalid query box overlaps nothing
    for (const Body &b : bodies_)
        if (b.live && filter.accepts(b.filter) && broadPhaseBoxesOverlap(box, b.box))
            out.push_back(b.userData);
    std::sort(out.begin(), out.end());
}
}  // namespace hcd
