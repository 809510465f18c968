// SPDX-License-Identifier: BSD-3-Clause
// Node pairs waiting in a tree traversal: a per-query stack (fixed storage on the call stack, heap
// only if it ever overflows), and a queue nearest pair first for distances.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace hcd
{
struct NodePair
{
    std::uint32_t robot;
    std::uint32_t environment;
};

/// A node pair with a lower bound on the distance of their contents, computed once.
struct BoundedPair
{
    NodePair pair;
    double bound;
};

/// Lives on the caller's stack, so concurrent queries never share scratch memory.
template <class Item>
class BasicTraversalStack
{
public:
    bool empty() const { return size_ == 0 && overflow_.empty(); }
    void push(Item p)
    {
        if (size_ < fixed_.size())
            fixed_[size_++] = p;
        else
            overflow_.push_back(p);
    }
    Item pop()
    {
        if (!overflow_.empty())
        {
            Item p = overflow_.back();
            overflow_.pop_back();
            return p;
        }
        return fixed_[--size_];
    }

private:
    std::array<Item, 256> fixed_;
    std::size_t size_ = 0;
    std::vector<Item> overflow_;
};

using TraversalStack = BasicTraversalStack<NodePair>;

/// Node pairs by their lower bound, smallest first: best-first branch and bound for distances,
/// which expands only pairs whose bound is below the distance and stops at the first pair whose
/// bound reaches the best found. Kept in a query context (QueryContext::scratch), so a warmed-up
/// context allocates nothing.
class NearestPairQueue
{
public:
    void clear() { heap_.clear(); }
    bool empty() const { return heap_.empty(); }
    /// The smallest bound queued (the queue must not be empty).
    double nearestBound() const { return heap_.front().bound; }
    void push(const BoundedPair &p)
    {
        heap_.push_back(p);
        std::push_heap(heap_.begin(), heap_.end(), Farther{});
    }
    BoundedPair pop()
    {
        std::pop_heap(heap_.begin(), heap_.end(), Farther{});
        const BoundedPair p = heap_.back();
        heap_.pop_back();
        return p;
    }

private:
    /// A type rather than a function pointer, so that the heap's comparisons inline.
    struct Farther
    {
        bool operator()(const BoundedPair &x, const BoundedPair &y) const { return x.bound > y.bound; }
    };
    std::vector<BoundedPair> heap_;
};
}  // namespace hcd
