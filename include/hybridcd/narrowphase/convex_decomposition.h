// SPDX-License-Identifier: BSD-3-Clause
// Cutting a mesh into convex pieces for the LP narrow phase.
//
// The pieces are the leaves of a volume tree built with at most K triangles per leaf: the top-down
// split already groups nearby triangles, so each leaf's triangles form
// a compact cluster, and its convex hull (Qhull) is the piece. Every triangle lies in the piece of
// its leaf by construction. Each piece records its concavity: how far its hull surface stands out
// from the triangles it covers (0 when the triangles are the hull, e.g. a single triangle or a
// convex closed cluster), measured on points spread over every hull facet
// (concavitySamplesPerEdge).
//
// The leaves come in as plain data (the tree's triangle order and each leaf's run of it), so this
// layer does not depend on the hierarchies; query/leaf_decomposition.h reads them off a VolumeTree.
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"
#include "hybridcd/narrowphase/convex_piece.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hcd
{
struct ConvexDecomposition
{
    std::vector<ConvexPiece> pieces;  ///< one per leaf, in the mesh's own frame
    std::vector<double> concavity;    ///< per piece, in mesh units: how far the hull surface stands out
    /// Per piece: an upper bound on the distance from ANY point of the hull (surface or inside) to
    /// the covered triangles. Two pieces whose hulls meet have triangles within the sum of their
    /// bounds of each other, which is what the LP checker's approximate mode relies on.
    std::vector<double> approximationBound;
    std::vector<std::int32_t> pieceOfNode;  ///< tree node -> piece index, -1 for internal nodes
    double seconds = 0.0;                   ///< time to build the hulls and measure concavity
};

/// One cluster of triangles wrapped into one piece: `count` entries of a triangle order, from
/// `first`, coming from tree node `node`.
struct TriangleCluster
{
    std::size_t node = 0;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

/// Hull of every cluster (in order) and its concavity. `triangleOrder` holds triangle indices of
/// `mesh`; `pieceOfNode` gets `nodeCount` entries, -1 for nodes with no cluster.
ConvexDecomposition decomposeClusters(const TriangleMesh &mesh, const std::vector<std::uint32_t> &triangleOrder,
                                      const std::vector<TriangleCluster> &clusters, std::size_t nodeCount);

/// A point in both of two intersecting triangles (within 1e-9 relative), from the LP on them as
/// flat convex pieces: the witness of a triangle contact.
Vec3 triangleContactPoint(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                          const Vec3 &b2);

/// The facets of a hull as polygons (vertices in order around each facet).
std::vector<std::vector<Vec3>> facetPolygons(const ConvexPiece &hull);

/// Volume enclosed by a hull (0 for flat ones).
double hullVolume(const ConvexPiece &hull);

/// Upper bound on max over points x of the hull of the distance from x to `triangles`: the largest
/// distance over a grid of interior points and the facet samples, plus the grid spacing (the
/// distance function is 1-Lipschitz, and every hull point is within one spacing of a sample).
/// Exactly 0 for a piece that is the hull of a single triangle.
double approximationBound(const ConvexPiece &hull, const TriangleMesh &mesh,
                          const std::vector<std::uint32_t> &triangles);

/// The facet sampling density the decomposition measures concavity with (samplesPerEdge of
/// measureConcavity): as fine as approximationBound's interior grid, 8 to 14 for a solid hull.
int concavitySamplesPerEdge(const ConvexPiece &hull);

/// Largest distance from points on the hull's facets (their corners, centroids and a grid of
/// `samplesPerEdge` x `samplesPerEdge` barycentric points) to the nearest of `triangles` of `mesh`.
double measureConcavity(const ConvexPiece &hull, const TriangleMesh &mesh, const std::vector<std::uint32_t> &triangles,
                        int samplesPerEdge = 4);
}  // namespace hcd
