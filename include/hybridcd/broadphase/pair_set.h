// SPDX-License-Identifier: BSD-3-Clause
// The set of overlapping body pairs that the sweep and prune keeps from one query to the next:
// open addressing with linear probing on 64-bit keys (the two body indices), erased by backward
// shifting so no tombstones build up under the constant inserts and erases of moving bodies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hcd
{
/// A set of unordered pairs of 32-bit body indices (i != j). Insert, erase and lookup take O(1)
/// expected time; the table doubles when half full and never shrinks (so once warm nothing is
/// allocated).
class BodyPairSet
{
public:
    /// The key of the pair {i, j}: min in the high half, max in the low half. Never kEmpty.
    static std::uint64_t key(std::uint32_t i, std::uint32_t j)
    {
        return i < j ? (std::uint64_t(i) << 32) | j : (std::uint64_t(j) << 32) | i;
    }
    static std::uint32_t first(std::uint64_t key) { return std::uint32_t(key >> 32); }
    static std::uint32_t second(std::uint64_t key) { return std::uint32_t(key); }

    /// Adds the pair (no effect if present); true when it was absent.
    bool insert(std::uint64_t key);
    /// Removes the pair (no effect if absent); true when it was present.
    bool erase(std::uint64_t key);
    bool contains(std::uint64_t key) const;
    /// Removes every pair that has `index` as one of its bodies (O(capacity)) and calls
    /// partner(j) for the other body j of each.
    template <typename F>
    void eraseBody(std::uint32_t index, F partner)
    {
        // Collect first: erasing while scanning would move keys past the scan.
        doomed_.clear();
        forEach([&](std::uint64_t k) {
            if (first(k) == index || second(k) == index)
                doomed_.push_back(k);
        });
        for (const std::uint64_t k : doomed_)
        {
            erase(k);
            partner(first(k) == index ? second(k) : first(k));
        }
    }
    std::size_t size() const { return size_; }

    /// Calls f(key) for every pair, in table order.
    template <typename F>
    void forEach(F f) const
    {
        for (const std::uint64_t k : slots_)
            if (k != kEmpty)
                f(k);
    }

private:
    static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
    std::size_t slotOf(std::uint64_t key) const
    {
        return std::size_t((key * 0x9E3779B97F4A7C15ULL) >> shift_) & (slots_.size() - 1);
    }
    void grow();
    void eraseSlot(std::size_t slot);

    std::vector<std::uint64_t> slots_;  // power-of-two size, kEmpty where free
    std::size_t size_ = 0;
    int shift_ = 64;
    std::vector<std::uint64_t> doomed_;  // eraseBody's scratch
};
}  // namespace hcd
