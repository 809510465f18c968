// SPDX-License-Identifier: BSD-3-Clause
// A per-query stack of node pairs: fixed storage on the call stack, heap only if it ever overflows.
#pragma once

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
}  // namespace hcd
