// SPDX-License-Identifier: BSD-3-Clause
// The robot's volumes and triangles mapped to world for one query, computed on first use.
#pragma once

#include "hybridcd/bv/box_lanes.h"
#include "hybridcd/bvh/volume_tree.h"
#include "hybridcd/query/query_context.h"
#include "hybridcd/query/stamped_slots.h"

#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace hcd
{
/// What mapping a volume type by a pose needs: the pose itself, or, when VolumeTraits<Volume>
/// declares a Placement (k-DOPs: per-rotation combinations), that, worked out once per query.
template <class Volume, class = void>
struct PlacementOf
{
    using Type = RigidTransform;
    static Type of(const RigidTransform &pose) { return pose; }
};
template <class Volume>
struct PlacementOf<Volume, std::void_t<typename VolumeTraits<Volume>::Placement>>
{
    using Type = typename VolumeTraits<Volume>::Placement;
    static Type of(const RigidTransform &pose) { return VolumeTraits<Volume>::placement(pose); }
};

/// A robot triangle in world coordinates with its axis-aligned bounds.
struct PlacedTriangle
{
    std::array<Vec3, 3> corners;
    Vec3 min, max;
};

/// View of one query's robot placement. Its storage is the query context's, reused across queries
/// (stamps mark what this query has computed), so nothing is allocated per query once the context
/// has warmed up. One PlacedRobot per volume type may be alive per context at a time:
/// constructing a new one invalidates the previous one.
template <class Volume>
class PlacedRobot
{
public:
    /// `laneBlocks`: how many blocks of lanes() the caller numbers (0 when it places none).
    PlacedRobot(const VolumeTree<Volume> &tree, const RigidTransform &worldFromRobot, QueryContext &context,
                std::size_t laneBlocks = 0)
        : tree_(tree),
          pose_(worldFromRobot),
          placement_(PlacementOf<Volume>::of(worldFromRobot)),
          s_(context.scratch<Scratch>()),
          query_(++s_.query)
    {
        s_.volumes.reserve(tree.nodes().size());
        s_.triangles.reserve(tree.mesh().triangleCount());
        s_.lanes.reserve(laneBlocks);
    }

    /// World-frame volume of robot tree node `node`.
    const Volume &volume(std::uint32_t node)
    {
        return s_.volumes.get(node, query_, [&](Volume &v) {
            v = VolumeTraits<Volume>::transformed(tree_.nodes()[node].volume, placement_);
        });
    }

    /// World-frame lanes (bv/box_lanes.h) of robot tree nodes nodes[0 .. count) (1 to 4), packed
    /// from their placed volumes on first use; `block` (below the constructor's laneBlocks) names
    /// that set of nodes in every query.
    const typename LanesOf<Volume>::Type &lanes(std::size_t block, const std::uint32_t *nodes, int count)
    {
        return s_.lanes.get(block, query_, [&](typename LanesOf<Volume>::Type &lanes) {
            lanes.count = 0;
            for (int k = 0; k < count; ++k)
                lanes.add(volume(nodes[k]), tree_.nodes()[nodes[k]].radius, nodes[k]);
            lanes.fill();
        });
    }

    /// World-frame corners of robot mesh triangle `t`, mapped by RigidTransform::apply (exactly as
    /// every other checker maps them), with their bounds.
    const PlacedTriangle &triangle(std::uint32_t t)
    {
        return s_.triangles.get(t, query_, [&](PlacedTriangle &p) {
            const TriangleMesh &mesh = tree_.mesh();
            for (int k = 0; k < 3; ++k)
                p.corners[k] = pose_.apply(mesh.corner(t, k));
            p.min = p.corners[0].cwiseMin(p.corners[1]).cwiseMin(p.corners[2]);
            p.max = p.corners[0].cwiseMax(p.corners[1]).cwiseMax(p.corners[2]);
        });
    }

private:
    struct Scratch
    {
        StampedSlots<Volume> volumes;
        StampedSlots<PlacedTriangle> triangles;
        StampedSlots<typename LanesOf<Volume>::Type> lanes;
        std::uint64_t query = 0;
    };

    const VolumeTree<Volume> &tree_;
    RigidTransform pose_;
    typename PlacementOf<Volume>::Type placement_;
    Scratch &s_;
    std::uint64_t query_;
};
}  // namespace hcd
