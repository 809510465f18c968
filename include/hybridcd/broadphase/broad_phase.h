// SPDX-License-Identifier: BSD-3-Clause
// What the broad phases share (sweep_and_prune.h, brute_force_broad_phase.h): body handles, the
// box a body is known by, the pair filter and the overlap rule.
//
// Overlap rule. A body is a closed axis-aligned box [lower, upper] in the world frame (any units,
// the caller's). Two boxes overlap when, on every axis, lower_a <= upper_b and lower_b <= upper_a,
// compared exactly on the stored doubles: boxes that touch (a shared face, edge or corner, or a
// zero-size box on another's face) overlap, and no tolerance is added anywhere, so the answer never
// depends on the scale of the coordinates. A caller that wants a margin grows its boxes itself.
// Infinite bounds are allowed (-inf/+inf): a half-space body such as the floor z <= 0 is the box
// [-inf, +inf] x [-inf, +inf] x [-inf, 0], and overlaps every box that reaches z <= 0. NaN bounds
// and lower > upper are refused (std::invalid_argument) when a box is added or updated.
#pragma once

#include "hybridcd/bv/aabb.h"

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace hcd
{
/// A body's box as its two corners, in the world frame: {p : lower <= p <= upper} componentwise.
/// Unlike `Aabb` (centre and half extents) it can be unbounded on one side only.
struct BroadPhaseBox
{
    Vec3 lower = Vec3::Zero();
    Vec3 upper = Vec3::Zero();

    /// The box of `box`: lower = center - halfExtents, upper = center + halfExtents, rounded once
    /// in double precision. Infinite half extents give the whole axis; a box at infinity on one
    /// side only cannot be written as an Aabb (centre +-inf, half extents inf give NaN): use the
    /// corners directly for half-space bodies.
    static BroadPhaseBox of(const Aabb &box) { return {box.center - box.halfExtents, box.center + box.halfExtents}; }

    /// True when no bound is NaN and lower <= upper on every axis.
    bool valid() const { return (lower.array() <= upper.array()).all(); }

    /// Throws std::invalid_argument naming `what` (the calling function) unless `valid()`.
    void requireValid(const char *what) const
    {
        if (!valid())
            throw std::invalid_argument(std::string(what) +
                                        ": a broad-phase box needs lower <= upper on every axis and no NaN bound");
    }
};

/// The overlap rule of every broad phase (closed boxes, exact comparisons; see the file comment).
inline bool broadPhaseBoxesOverlap(const BroadPhaseBox &a, const BroadPhaseBox &b)
{
    return a.lower.x() <= b.upper.x() && b.lower.x() <= a.upper.x() && a.lower.y() <= b.upper.y() &&
           b.lower.y() <= a.upper.y() && a.lower.z() <= b.upper.z() && b.lower.z() <= a.upper.z();
}

/// Which pairs a broad phase reports, Jolt-style: every body belongs to the categories in
/// `category` (bits) and wants pairs with bodies of the categories in `collidesWith`. A pair is
/// reported when each body's category meets the other's `collidesWith`.
struct BroadPhaseFilter
{
    /// Category bit of bodies that move (the default).
    static constexpr std::uint32_t kDynamic = 1u;
    /// Category bit of bodies that never move relative to each other (the environment).
    static constexpr std::uint32_t kStatic = 2u;

    std::uint32_t category = kDynamic;
    std::uint32_t collidesWith = ~0u;

    /// A moving body: paired with every body.
    static constexpr BroadPhaseFilter dynamicBody() { return {kDynamic, ~0u}; }
    /// A static body: paired with every body except other static ones, so that static-static pairs
    /// are never reported.
    static constexpr BroadPhaseFilter staticBody() { return {kStatic, ~kStatic}; }
    /// For box queries: accepts every body that accepts anything.
    static constexpr BroadPhaseFilter everything() { return {~0u, ~0u}; }

    /// True when a pair of bodies with these filters is reported (symmetric).
    constexpr bool accepts(const BroadPhaseFilter &other) const
    {
        return (category & other.collidesWith) != 0u && (other.category & collidesWith) != 0u;
    }
};

/// A body of a broad phase: an index into the phase's own table, valid from `add` until `remove`
/// (indices of removed bodies are reused by later adds).
struct BodyHandle
{
    static constexpr std::uint32_t kInvalid = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t index = kInvalid;

    bool valid() const { return index != kInvalid; }
    friend bool operator==(BodyHandle a, BodyHandle b) { return a.index == b.index; }
    friend bool operator!=(BodyHandle a, BodyHandle b) { return a.index != b.index; }
};

/// A reported pair: the two bodies' user data, ordered (min, max).
using UserDataPair = std::pair<std::uint32_t, std::uint32_t>;
}  // namespace hcd
