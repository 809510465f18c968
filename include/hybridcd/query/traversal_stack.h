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
        // Sift up: a four-way heap is half as deep as a binary one, and its four children of a
        // node share a cache line or two.
        std::size_t i = heap_.size();
        heap_.push_back(p);
        while (i > 0)
        {
            const std::size_t parent = (i - 1) / 4;
            if (!(p.bound < heap_[parent].bound))
                break;
            heap_[i] = heap_[parent];
            i = parent;
        }
        heap_[i] = p;
    }
    BoundedPair pop()
    {
        const BoundedPair top = heap_.front();
        const BoundedPair last = heap_.back();
        heap_.pop_back();
        const std::size_t n = heap_.size();
        if (n == 0)
            return top;
        // Sift the last element down from the root.
        std::size_t i = 0;
        for (;;)
        {
            const std::size_t first = 4 * i + 1;
            if (first >= n)
                break;
            std::size_t smallest = first;
            const std::size_t end = std::min(first + 4, n);
            for (std::size_t c = first + 1; c < end; ++c)
                if (heap_[c].bound < heap_[smallest].bound)
                    smallest = c;
            if (!(heap_[smallest].bound < last.bound))
                break;
            heap_[i] = heap_[smallest];
            i = smallest;
        }
        heap_[i] = last;
        return top;
    }

private:
    std::vector<BoundedPair> heap_;
};
}  // namespace hcd
