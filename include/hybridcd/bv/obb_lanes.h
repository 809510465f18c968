// SPDX-License-Identifier: BSD-3-Clause
// Up to four oriented boxes side by side, tested against one box at once (SIMD, picked at run time).
#pragma once

#include "hybridcd/bv/obb.h"

#include <cstdint>

namespace hcd
{
/// Four boxes stored one array per coordinate, so that a test of one box against all of them runs
/// in SIMD lanes: a tree keeps one per inner node, holding the boxes two levels down, and a query
/// tests a node of the other tree against them in one call instead of popping and testing each.
/// Lanes past `count` repeat lane 0 (finite numbers) and are masked out of every answer.
struct alignas(64) ObbLanes
{
    static constexpr int kLanes = 4;
    double center[3][kLanes];       ///< centre coordinate c, lane k: center[c][k]
    double axes[3][3][kLanes];      ///< row r of axis (column) a, lane k: axes[r][a][k]
    double halfExtents[3][kLanes];  ///< along each axis
    double radius[kLanes];          ///< a sphere about the centre holding the box's contents
    std::uint32_t node[kLanes];     ///< what the lane stands for (a tree node index)
    int count = 0;                  ///< lanes in use, 0 to kLanes

    /// Appends a lane (count < kLanes); fill() completes the unused ones.
    void add(const Obb &box, double sphereRadius, std::uint32_t nodeIndex);
    /// Copies lane 0 into the lanes past `count` (count >= 1).
    void fill();
};

/// Bit k set when lane k (k < count) may overlap `a`: their spheres (radii `aRadius` and
/// lanes.radius[k]) come within `tolerance` and no separating axis of the two boxes (face and edge
/// axes) separates them by more than `tolerance`. Conservative as obbsOverlap is (the same
/// arithmetic and the same 1e-12 on |R|, in the widest SIMD instruction set the machine has).
unsigned obbLanesOverlap(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance);

/// obbLanesOverlap lane by lane with obbsOverlap and the sphere test: the reference the SIMD
/// kernel is tested against.
unsigned obbLanesOverlapReference(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance);
}  // namespace hcd
