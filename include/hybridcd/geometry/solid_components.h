// SPDX-License-Identifier: BSD-3-Clause
// Solid objects: the connected components of a mesh, which of them are closed, and exact
// point-in-solid queries against the closed ones.
//
// A closed component bounds a volume, and a robot placed wholly inside it collides even though no
// pair of triangles meets. Orientation cannot tell inside from outside here (SketchUp exports every
// face twice, once reversed), so "inside" is decided by parity: a point is inside when a ray from
// it crosses the component's distinct triangles an odd number of times. The crossing tests use
// orientation predicates with exact signs, a ray that grazes an edge or vertex or runs within a
// triangle's plane is replaced by another, and points on the surface count as inside.
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace hcd
{
/// One connected component of a mesh (triangles sharing vertices, after welding), or one closed
/// shell of one (see meshComponents()), closed or not.
struct MeshComponent
{
    std::vector<std::uint32_t> triangles;  ///< indices into TriangleMesh::triangles, ascending
    bool closed = false;                   ///< see meshComponents()
    BoundingBox bounds;                    ///< of the component's triangles
};

/// Splits the mesh into connected components (union-find over shared vertices; vertices with
/// identical coordinates count as one, so the mesh need not be welded) and marks each closed when,
/// after removing triangles that repeat another with the same vertex set (either orientation),
/// every undirected edge is used by an even, non-zero number of the remaining triangles. A closed
/// component made of closed shells that meet only at vertices, or at edges more than two faces
/// share, is split into those shells, each a closed component: a solid inside another that touches
/// it at a corner is then a solid of its own, and a point inside both is inside (parity over the
/// two would call it outside). A component left open that way is still closed when its faces
/// without a reverse (the same corners in the other order) close: solids that share a face hold it
/// once in each orientation, and the faces left bound their union (a point inside either solid is
/// inside), while a double-sided sheet on a closed solid stays a surface. Components are ordered by
/// their smallest triangle index.
std::vector<MeshComponent> meshComponents(const TriangleMesh &mesh);

/// Exact point-in-solid queries against the closed components of a mesh. Immutable after
/// construction, cheap to copy (the index is shared), and safe to query from several threads.
class SolidQuery
{
public:
    /// Finds the components of `mesh` and indexes the closed ones for point queries.
    explicit SolidQuery(std::shared_ptr<const TriangleMesh> mesh);

    /// Number of closed components (the solids).
    std::size_t closedComponentCount() const;

    /// Every component of the mesh, closed or open, in meshComponents() order.
    const std::vector<MeshComponent> &components() const;

    /// The mesh the query was built for.
    const TriangleMesh &mesh() const { return *mesh_; }

    /// True if p is inside or on the surface of some closed component.
    bool insideAnySolid(const Vec3 &p) const { return solidContaining(p) >= 0; }

    /// False when p lies outside the bounding box of every closed component, which rules out
    /// insideAnySolid(p) without casting a ray; true otherwise.
    bool withinSolidBounds(const Vec3 &p) const;

    /// Index into components() of a closed component containing p (inside or on its surface), or
    /// -1. When closed components nest or overlap, the lowest such index.
    int solidContaining(const Vec3 &p) const;

    /// True if p is inside or on the surface of components()[component]; false when that component
    /// is open. Throws std::out_of_range for an index past components().
    bool insideComponent(std::size_t component, const Vec3 &p) const;

    /// Fraction of the mesh's bounding-box volume that lies inside closed components, estimated
    /// from `samples` uniform points (0 when samples is 0). Point i is min + (max - min) * (u, v, w)
    /// with u, v, w from three successive draws r of std::mt19937_64(seed), each (r >> 11) * 2^-53,
    /// so the estimate is the same with every standard library.
    double solidVolumeFraction(std::size_t samples, std::uint64_t seed) const;

private:
    struct Index;  // components and the per-solid ray-casting grids (solid_components.cpp)

    std::shared_ptr<const TriangleMesh> mesh_;
    std::shared_ptr<const Index> index_;
};

/// One vertex of each non-empty component of the query's mesh, in components() order: a point
/// that decides, once surfaces are disjoint, on which side of every solid the component lies.
std::vector<Vec3> firstVertexOfEachComponent(const SolidQuery &solids);

/// Up to `perComponent` vertices of each non-empty component of the query's mesh, spread over its
/// triangles (the first corner of every k-th one), in components() order, each list starting with
/// firstVertexOfEachComponent's vertex: probes of which one usually lies in a free grid cell.
std::vector<std::vector<Vec3>> verticesSpreadOverEachComponent(const SolidQuery &solids, std::size_t perComponent);
}  // namespace hcd
