// SPDX-License-Identifier: BSD-3-Clause
// An indexed triangle mesh: the geometry every hierarchy and checker is built from.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace hcd
{
/// Axis-aligned box [min, max]; empty when min > max.
struct BoundingBox
{
    Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

    void extend(const Vec3 &p)
    {
        min = min.cwiseMin(p);
        max = max.cwiseMax(p);
    }
    bool empty() const { return (min.array() > max.array()).any(); }
};

/// Per axis, the gap between the boxes [aMin, aMax] and [bMin, bMax] (zero where their ranges
/// overlap); its norm is the Euclidean distance between the boxes. A point is a box of no extent.
inline Vec3 boxSeparation(const Vec3 &aMin, const Vec3 &aMax, const Vec3 &bMin, const Vec3 &bMax)
{
    return (aMin - bMax).cwiseMax(bMin - aMax).cwiseMax(Vec3::Zero());
}

/// Triangles over a shared vertex array, in the mesh's own frame. Triangles are never degenerate
/// when the mesh comes from the loader (those are dropped and counted there).
struct TriangleMesh
{
    using Triangle = std::array<std::uint32_t, 3>;

    std::vector<Vec3> vertices;
    std::vector<Triangle> triangles;

    std::size_t triangleCount() const { return triangles.size(); }
    bool empty() const { return triangles.empty(); }
    const Vec3 &corner(std::size_t triangle, int k) const { return vertices[triangles[triangle][k]]; }

    BoundingBox bounds() const;

    /// Largest distance of a vertex from the origin of the mesh frame (0 for an empty mesh).
    double radiusAboutOrigin() const;
    /// Largest distance of a vertex from the z axis (the largest |(x, y)|).
    double radiusAboutZAxis() const;

    /// Bytes held by the vertex and triangle arrays.
    std::size_t memoryBytes() const;
};

/// Edge-manifold closedness: after removing triangles that repeat another one with the same or
/// reversed vertex order (SketchUp exports every face twice), every undirected edge is shared by an
/// even, non-zero number of triangles. Orientation is not required to be consistent.
bool isClosed(const TriangleMesh &mesh);

/// True when the faces (corner triples, each sorted ascending, no face repeated) use every
/// undirected edge an even, non-zero number of times: the closedness rule of isClosed().
bool everyEdgeUsedEvenly(const std::vector<TriangleMesh::Triangle> &sortedFaces);

/// Merges vertices with identical coordinates and drops triangles that become degenerate
/// (collinear or repeated corners, decided exactly). Returns the number of triangles dropped.
std::size_t weldAndDropDegenerate(TriangleMesh &mesh);

/// A mesh as the query structures use it: every triangle that repeats an earlier one's corner
/// indices, in the same or another order, removed (SketchUp exports every face twice, once
/// reversed). The point set is unchanged, so collision and distance answers are the same as on
/// the source mesh; solids come from the source mesh (meshComponents()).
struct DistinctFaceMesh
{
    /// The source mesh itself when no face repeats; otherwise a copy without the repeats, with the
    /// same vertices and the kept triangles in their source order (the first of each group is kept).
    std::shared_ptr<const TriangleMesh> mesh;
    /// Index in the source mesh of each triangle of `mesh`; empty when nothing was dropped.
    std::vector<std::uint32_t> sourceTriangle;
    /// Triangles of the source mesh left out.
    std::size_t dropped = 0;

    std::uint32_t source(std::uint32_t t) const { return sourceTriangle.empty() ? t : sourceTriangle[t]; }
};

/// Faces are compared by vertex index, so vertices should be welded first (the loader does).
DistinctFaceMesh withoutRepeatedFaces(std::shared_ptr<const TriangleMesh> mesh);
}  // namespace hcd
