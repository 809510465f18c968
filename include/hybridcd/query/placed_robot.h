// SPDX-License-Identifier: BSD-3-Clause
// The robot's volumes and triangles mapped to world for one query, computed on first use.
#pragma once

#include "hybridcd/bvh/volume_tree.h"

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
/// allocated per query once a thread has warmed up. One PlacedRobot per volume type may be alive
/// per thread at a time; constructing a new one invalidates the previous one.
template <class Volume>
class PlacedRobot
{
public:
    PlacedRobot(const VolumeTree<Volume> &tree, const RigidTransform &worldFromRobot)
        : tree_(tree), pose_(worldFromRobot), s_(scratch()), query_(++s_.query)
    {
        const std::size_t nodes = tree.nodes().size(), triangles = tree.mesh().triangleCount();
        if (s_.volumes.size() < nodes)
        {
            s_.volumes.resize(nodes);
            s_.volumeStamps.resize(nodes, 0);
        }
        if (s_.triangles.size() < triangles)
        {
            s_.triangles.resize(triangles);
            s_.triangleStamps.resize(triangles, 0);
        }
    }

    /// World-frame volume of robot tree node `node`.
    const Volume &volume(std::uint32_t node)
    {
        if (s_.volumeStamps[node] != query_)
        {
            s_.volumes[node] = VolumeTraits<Volume>::transformed(tree_.nodes()[node].volume, pose_);
            s_.volumeStamps[node] = query_;
        }
        return s_.volumes[node];
    }

    /// World-frame corners of robot mesh triangle `t`, mapped by RigidTransform::apply (exactly as
    /// every other checker maps them), with their bounds.
    const PlacedTriangle &triangle(std::uint32_t t)
    {
        PlacedTriangle &p = s_.triangles[t];
        if (s_.triangleStamps[t] != query_)
        {
            const TriangleMesh &mesh = tree_.mesh();
            for (int k = 0; k < 3; ++k)
                p.corners[k] = pose_.apply(mesh.corner(t, k));
            p.min = p.corners[0].cwiseMin(p.corners[1]).cwiseMin(p.corners[2]);
            p.max = p.corners[0].cwiseMax(p.corners[1]).cwiseMax(p.corners[2]);
            s_.triangleStamps[t] = query_;
        }
        return p;
    }

private:
    struct Scratch
    {
        std::vector<Volume> volumes;
        std::vector<std::uint64_t> volumeStamps;
        std::vector<PlacedTriangle> triangles;
        std::vector<std::uint64_t> triangleStamps;
        std::uint64_t query = 0;
    };
    static Scratch &scratch()
    {
        thread_local Scratch s;
        return s;
    }

    const VolumeTree<Volume> &tree_;
    RigidTransform pose_;
    Scratch &s_;
    std::uint64_t query_;
};
}  // namespace hcd
