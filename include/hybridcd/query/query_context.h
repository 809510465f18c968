// SPDX-License-Identifier: BSD-3-Clause
// What one stream of queries carries from query to query, owned by the caller.
#pragma once

#include "hybridcd/narrowphase/small_lp.h"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace hcd
{
/// Work counters that queries add to.
struct QueryStats
{
    std::uint64_t boundingVolumeTests = 0;
    std::uint64_t primitiveTests = 0;
};

/// Scratch memory, work counters and (as they come) coherence caches of one stream of queries:
/// one per thread, per planner or per motion, as Box2D hands its caller a b2SimplexCache.
/// Checkers are immutable and shared between threads; everything a query writes lives here, so
/// that a warmed-up context makes queries allocate nothing. A context serves one query at a
/// time; give each thread its own (QueryContextPool hands them out when the threads are not
/// yours, as with OMPL's parallel planners). Any context works with any checker.
class QueryContext
{
public:
    QueryContext() = default;
    QueryContext(const QueryContext &) = delete;
    QueryContext &operator=(const QueryContext &) = delete;
    QueryContext(QueryContext &&) noexcept = default;
    QueryContext &operator=(QueryContext &&) noexcept = default;

    /// Work counters, added to by every query made with this context.
    QueryStats stats;

    /// The narrow phase's LP scratch.
    LpWorkspace &lp() { return lp_; }

    /// This context's scratch of type `T` (default-constructed on first use, then kept): the
    /// query code's own per-type buffers, such as the robot placed for one volume type.
    template <class T>
    T &scratch()
    {
        const std::size_t slot = slotOf<T>();
        if (slot >= slots_.size())
            slots_.resize(slot + 1);
        if (!slots_[slot])
            slots_[slot] = std::make_shared<T>();
        return *static_cast<T *>(slots_[slot].get());
    }

private:
    using Slot = std::shared_ptr<void>;  // type-erased owner; never shared (contexts do not copy)

    // A small index per scratch type, handed out once per process on first use (a
    // function-local static: initialised once, thread-safely, never written afterwards).
    static std::size_t nextSlot()
    {
        static std::atomic<std::size_t> next{0};
        return next.fetch_add(1, std::memory_order_relaxed);
    }
    template <class T>
    static std::size_t slotOf()
    {
        static const std::size_t slot = nextSlot();
        return slot;
    }

    LpWorkspace lp_;
    std::vector<Slot> slots_;
};
}  // namespace hcd
