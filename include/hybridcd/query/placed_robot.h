// SPDX-License-Identifier: BSD-3-Clause
// The robot's boxes and triangles mapped to world for one query, computed on first use.
#pragma once

#include "hybridcd/bvh/obb_tree.h"

#include <array>
#include <cstdint>
#include <vector>

namespace hcd
{
/// A robot triangle in world coordinates with its axis-aligned bounds.
struct PlacedTriangle
{
    std::array<Vec3, 3> corners;
    Vec3 min, max;
};

/// View of one query's robot placement. Storage is per thread and reused across queries (stamps
/// mark what this query has computed), so concurrent queries never share scratch and nothing is
/// allocated per query once a thread has warmed up. One PlacedRobot may be alive per thread at a
/// time; a new one invalidates the previous one.
class PlacedRobot
{
public:
    PlacedRobot(const ObbTree &tree, const RigidTransform &worldFromRobot);

    /// World-frame box of robot tree node `node`.
    const Obb &box(std::uint32_t node);

    /// World-frame corners of robot mesh triangle `triangle`, mapped by RigidTransform::apply
    /// (exactly as every other checker maps them).
    const PlacedTriangle &triangle(std::uint32_t triangle);

private:
    struct Scratch
    {
        std::vector<Obb> boxes;
        std::vector<std::uint64_t> boxStamps;
        std::vector<PlacedTriangle> triangles;
        std::vector<std::uint64_t> triangleStamps;
        std::uint64_t query = 0;
    };
    static Scratch &scratch();

    const ObbTree &tree_;
    RigidTransform pose_;
    Scratch &s_;
    std::uint64_t query_;
};
}  // namespace hcd
