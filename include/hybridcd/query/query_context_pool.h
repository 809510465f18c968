// SPDX-License-Identifier: BSD-3-Clause
// Query contexts lent to threads the caller does not control.
#pragma once

#include "hybridcd/query/query_context.h"

#include <array>
#include <atomic>
#include <memory>

namespace hcd
{
/// Lends query contexts to whichever threads ask: OMPL calls one validity checker from all the
/// threads of a parallel planner, so the adapter cannot hand each thread a context of its own.
/// A query borrows a context for its duration and returns it; contexts are reused, so a warm pool
/// allocates nothing. Lock-free: borrowing and returning are one atomic exchange each when a
/// context is idle. Thread-safe.
class QueryContextPool
{
public:
    QueryContextPool() = default;
    QueryContextPool(const QueryContextPool &) = delete;
    QueryContextPool &operator=(const QueryContextPool &) = delete;
    ~QueryContextPool()
    {
        for (auto &slot : idle_)
            delete slot.load(std::memory_order_relaxed);
    }

    /// A borrowed context, returned to the pool when the lease ends.
    class Lease
    {
    public:
        Lease(Lease &&other) noexcept : pool_(other.pool_), context_(other.context_) { other.context_ = nullptr; }
        Lease(const Lease &) = delete;
        Lease &operator=(const Lease &) = delete;
        Lease &operator=(Lease &&) = delete;
        ~Lease()
        {
            if (context_)
                pool_.giveBack(context_);
        }
        QueryContext &operator*() const { return *context_; }
        QueryContext *operator->() const { return context_; }

    private:
        friend class QueryContextPool;
        Lease(QueryContextPool &pool, QueryContext *context) : pool_(pool), context_(context) {}
        QueryContextPool &pool_;
        QueryContext *context_;
    };

    /// An idle context, or a new one when every context is in use.
    Lease borrow()
    {
        for (auto &slot : idle_)
            if (slot.load(std::memory_order_relaxed) != nullptr)
                if (QueryContext *c = slot.exchange(nullptr, std::memory_order_acquire))
                    return Lease(*this, c);
        return Lease(*this, new QueryContext());
    }

private:
    void giveBack(QueryContext *context)
    {
        for (auto &slot : idle_)
        {
            QueryContext *empty = nullptr;
            if (slot.compare_exchange_strong(empty, context, std::memory_order_release, std::memory_order_relaxed))
                return;
        }
        delete context;  // more threads than slots: the extra context is not kept
    }

    // Idle contexts; as many as the threads that query at once, up to the array's size.
    std::array<std::atomic<QueryContext *>, 64> idle_{};
};
}  // namespace hcd
