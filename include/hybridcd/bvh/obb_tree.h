// SPDX-License-Identifier: BSD-3-Clause
// A binary tree of oriented bounding boxes over the triangles of one mesh.
//
// Build: top-down. Each node's box is the smaller of the principal-axis box of its vertices and the
// axis-aligned box. The node's triangles are split across the longest box axis at the mean of
// their centroids (Gottschalk's rule); if every centroid lands on one side, at the median instead.
// Nodes are stored in one array with the two children of a node adjacent, leaves hold a run of the
// tree's reordered triangle list.
#pragma once

#include "hybridcd/bv/obb.h"
#include "hybridcd/geometry/triangle_mesh.h"

#include <cstdint>
#include <memory>

namespace hcd
{
class ObbTree
{
public:
    struct Node
    {
        Obb box;
        double radius = 0.0;  ///< of the box's circumscribed sphere, for a cheap first reject
        std::int32_t firstChild = -1;  ///< index of the left child (right = +1), -1 for a leaf
        std::uint32_t firstTriangle = 0;  ///< leaves: first index into triangleOrder()
        std::uint32_t triangleCount = 0;

        bool isLeaf() const { return firstChild < 0; }
    };

    /// Builds over `mesh`, which must outlive the tree. Leaves hold at most `maxLeafTriangles`.
    explicit ObbTree(std::shared_ptr<const TriangleMesh> mesh, unsigned maxLeafTriangles = 1);

    const TriangleMesh &mesh() const { return *mesh_; }
    const std::vector<Node> &nodes() const { return nodes_; }
    const Node &root() const { return nodes_.front(); }
    bool empty() const { return nodes_.empty(); }
    /// Mesh triangle indices in leaf order.
    const std::vector<std::uint32_t> &triangleOrder() const { return order_; }

    std::size_t depth() const { return depth_; }
    double buildSeconds() const { return buildSeconds_; }
    std::size_t memoryBytes() const;

private:
    void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, std::size_t level, std::vector<Vec3> &scratch);

    std::shared_ptr<const TriangleMesh> mesh_;
    unsigned maxLeafTriangles_;
    std::vector<Node> nodes_;
    std::vector<std::uint32_t> order_;
    std::vector<Vec3> centroids_;
    std::size_t depth_ = 0;
    double buildSeconds_ = 0.0;
};
}  // namespace hcd
