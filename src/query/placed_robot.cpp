// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/placed_robot.h"

namespace hcd
{
PlacedRobot::Scratch &PlacedRobot::scratch()
{
    thread_local Scratch s;
    return s;
}

PlacedRobot::PlacedRobot(const ObbTree &tree, const RigidTransform &worldFromRobot)
    : tree_(tree), pose_(worldFromRobot), s_(scratch()), query_(++s_.query)
{
    const std::size_t nodes = tree.nodes().size(), triangles = tree.mesh().triangleCount();
    if (s_.boxes.size() < nodes)
    {
        s_.boxes.resize(nodes);
        s_.boxStamps.resize(nodes, 0);
    }
    if (s_.triangles.size() < triangles)
    {
        s_.triangles.resize(triangles);
        s_.triangleStamps.resize(triangles, 0);
    }
}

const Obb &PlacedRobot::box(std::uint32_t node)
{
    if (s_.boxStamps[node] != query_)
    {
        s_.boxes[node] = tree_.nodes()[node].box.transformed(pose_);
        s_.boxStamps[node] = query_;
    }
    return s_.boxes[node];
}

const PlacedTriangle &PlacedRobot::triangle(std::uint32_t t)
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
}  // namespace hcd
