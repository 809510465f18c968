// SPDX-License-Identifier: BSD-3-Clause
// Up to four boxes side by side, tested against one box at once (SIMD, the instruction set picked
// at run time): oriented boxes (ObbLanes) and axis-aligned ones (AabbLanes).
#pragma once

#include "hybridcd/bv/aabb.h"
#include "hybridcd/bv/obb.h"

#include <cstdint>

namespace hcd
{
/// Four boxes of `Fields` numbers each, stored one array per number, so that a test of one box
/// against all of them runs in SIMD lanes: a tree keeps one per inner node, holding the boxes two
/// levels down, and a query tests a node of the other tree against them in one call instead of
/// popping and testing each. Lanes past `count` repeat lane 0 (finite numbers) and are masked out
/// of every answer.
template <int Fields>
struct alignas(64) BoxLanes
{
    static constexpr int kLanes = 4;
    double field[Fields][kLanes];  ///< number f of the box in lane k: field[f][k]
    double radius[kLanes];         ///< a sphere about the box's centre holding its contents
    std::uint32_t node[kLanes];    ///< what the lane stands for (a tree node index)
    int count = 0;                 ///< lanes in use, 0 to kLanes

    /// Copies lane 0 into the lanes past `count` (count >= 1).
    void fill()
    {
        for (int k = count; k < kLanes; ++k)
        {
            for (int f = 0; f < Fields; ++f)
                field[f][k] = field[f][0];
            radius[k] = radius[0];
            node[k] = node[0];
        }
    }
};

/// Oriented boxes: fields 0-2 the centre, 3 + 3r + a row r of axis (column) a, 12-14 the half
/// extents.
struct ObbLanes : BoxLanes<15>
{
    static constexpr int kCenter = 0, kAxes = 3, kHalfExtents = 12;
    /// Appends a lane (count < kLanes); fill() completes the unused ones.
    void add(const Obb &box, double sphereRadius, std::uint32_t nodeIndex);
    /// The box in lane k.
    Obb box(int k) const;
};

/// Axis-aligned boxes: fields 0-2 the centre, 3-5 the half extents.
struct AabbLanes : BoxLanes<6>
{
    static constexpr int kCenter = 0, kHalfExtents = 3;
    void add(const Aabb &box, double sphereRadius, std::uint32_t nodeIndex);
    Aabb box(int k) const;
};

/// Bit k set when lane k (k < count) may overlap `a`: their spheres (radii `aRadius` and
/// lanes.radius[k]) come within `tolerance` and no separating axis of the two boxes (face and edge
/// axes) separates them by more than `tolerance`. The same arithmetic as obbsOverlap (and its
/// 1e-12 on |R|), so the same answer, in the widest SIMD instruction set the machine has.
unsigned lanesOverlap(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance);
/// The same for axis-aligned boxes, as aabbsOverlap decides it.
unsigned lanesOverlap(const AabbLanes &lanes, const Aabb &a, double aRadius, double tolerance);

/// lanesOverlap lane by lane with the sphere test and obbsOverlap or aabbsOverlap: the reference
/// the SIMD kernels are tested against.
unsigned lanesOverlapReference(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance);
unsigned lanesOverlapReference(const AabbLanes &lanes, const Aabb &a, double aRadius, double tolerance);

/// Lower bounds on the distance from `a` to each lane's box, bound[k] for k < count (the rest of
/// bound[0 .. kLanes) is overwritten with unspecified values): the larger of the sphere gap (centres'
/// distance minus both radii and `tolerance`) and obbDistanceLowerBound(a, box, tolerance) with all
/// its stages, in the same arithmetic, so the same numbers as lanesDistanceLowerBoundReference.
void lanesDistanceLowerBound(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance, double *bound);
/// The same with aabbDistanceLowerBound.
void lanesDistanceLowerBound(const AabbLanes &lanes, const Aabb &a, double aRadius, double tolerance, double *bound);
/// lanesDistanceLowerBound lane by lane with the scalar bounds: the kernels' reference.
void lanesDistanceLowerBoundReference(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance,
                                      double *bound);
void lanesDistanceLowerBoundReference(const AabbLanes &lanes, const Aabb &a, double aRadius, double tolerance,
                                      double *bound);

/// The lanes of a volume type, if it has them: boxes of that type four at a time.
template <class Volume>
struct LanesOf
{
    struct None
    {
    };
    using Type = None;
    static constexpr bool kUsed = false;
};
template <>
struct LanesOf<Obb>
{
    using Type = ObbLanes;
    static constexpr bool kUsed = true;
};
template <>
struct LanesOf<Aabb>
{
    using Type = AabbLanes;
    static constexpr bool kUsed = true;
};
}  // namespace hcd
