// SPDX-License-Identifier: BSD-3-Clause
// Per-query values cached in reusable slots, valid while their stamp matches the query.
#pragma once

#include <cstdint>
#include <vector>

namespace hcd
{
/// Slots indexed by element (node, triangle, piece), each holding a value computed during one
/// query. A slot is current when its stamp equals the query's id, so nothing is cleared between
/// queries and storage is reused once it has grown. Lives in a QueryContext.
template <class T>
class StampedSlots
{
public:
    /// Makes slots 0 .. count-1 available (stale until computed).
    void reserve(std::size_t count)
    {
        if (values_.size() < count)
        {
            values_.resize(count);
            stamps_.resize(count, 0);
        }
    }

    /// The value of slot `i` for query `query`, computed by `compute(T &)` on first use.
    template <class Compute>
    T &get(std::size_t i, std::uint64_t query, Compute &&compute)
    {
        if (stamps_[i] != query)
        {
            compute(values_[i]);
            stamps_[i] = query;
        }
        return values_[i];
    }

private:
    std::vector<T> values_;
    std::vector<std::uint64_t> stamps_;
};
}  // namespace hcd
