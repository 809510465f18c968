// SPDX-License-Identifier: BSD-3-Clause
// An octree of the environment's volume (seed §3.1): cubes subdivided where triangles are.
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace hcd
{
/// True unless a separating axis (the cube's three faces, the triangle's normal, the nine edge
/// crosses) parts triangle (a, b, c) from the cube {|p - center| <= halfSide} by more than
/// `tolerance` (Akenine-Moller's test, made conservative: it may keep a triangle that misses).
bool triangleTouchesCube(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &center, double halfSide,
                         double tolerance);

/// Cells are cubes in the world frame. The root is the environment's bounding cube; a cell is
/// split into eight when it holds more than `leafTriangles` triangles and lies above `maxDepth`,
/// unless one octant would still hold all of them (triangles meeting at a vertex: splitting would
/// not part them) or the cells would list the triangles more than 32 times each on average (a
/// bound on memory). Only the children that hold triangles are kept (empty space has no cells). Each leaf lists
/// every triangle that touches it, so a triangle spanning several leaves is listed in each.
class Octree
{
public:
    struct Limits
    {
        unsigned maxDepth = 10;      ///< levels below the root
        unsigned leafTriangles = 8;  ///< a cell with more is split (above maxDepth)
    };

    struct Cell
    {
        Vec3 center = Vec3::Zero();
        double halfSide = 0.0;
        std::int32_t firstChild = -1;     ///< index of the first child (they are adjacent), -1 for a leaf
        std::uint32_t childCount = 0;     ///< 1 to 8 occupied children
        std::uint32_t firstTriangle = 0;  ///< a leaf's run in triangleReferences()
        std::uint32_t triangleCount = 0;

        bool isLeaf() const { return firstChild < 0; }
    };

    Octree(std::shared_ptr<const TriangleMesh> mesh, Limits limits);

    const TriangleMesh &mesh() const { return *mesh_; }
    const std::vector<Cell> &cells() const { return cells_; }
    bool empty() const { return cells_.empty(); }
    /// Mesh triangle indices, leaf by leaf.
    const std::vector<std::uint32_t> &triangleReferences() const { return references_; }
    std::size_t leafCount() const { return leaves_; }
    std::size_t depth() const { return depth_; }
    double buildSeconds() const { return buildSeconds_; }
    std::size_t memoryBytes() const
    {
        return cells_.capacity() * sizeof(Cell) + references_.capacity() * sizeof(std::uint32_t);
    }

private:
    void build(std::uint32_t cell, std::vector<std::uint32_t> triangles, std::size_t level);
    void makeLeaf(std::uint32_t cell, const std::vector<std::uint32_t> &triangles);

    std::shared_ptr<const TriangleMesh> mesh_;
    Limits limits_;
    double tolerance_ = 0.0;  ///< for the triangle/cube tests: rounding at the mesh's magnitude
    std::vector<Cell> cells_;
    std::vector<std::uint32_t> references_;
    std::size_t leaves_ = 0;
    std::size_t listed_ = 0;  ///< triangle listings of every cell made so far (for the memory bound)
    std::size_t depth_ = 0;
    double buildSeconds_ = 0.0;
};
}  // namespace hcd
