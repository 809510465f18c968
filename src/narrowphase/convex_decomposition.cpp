// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/convex_decomposition.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/narrowphase/linear_program.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace hcd
{
namespace
{
double distanceToTriangles(const Vec3 &p, const TriangleMesh &mesh, const std::vector<std::uint32_t> &triangles)
{
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t t : triangles)
        best = std::min(
            best, (p - closestPointOnTriangle(p, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2))).norm());
    return best;
}
}  // namespace

Vec3 triangleContactPoint(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                          const Vec3 &b2)
{
    return intersectConvexPieces(ConvexPiece::hullOf({a0, a1, a2}), ConvexPiece::hullOf({b0, b1, b2})).witness;
}

std::vector<std::vector<Vec3>> facetPolygons(const ConvexPiece &hull)
{
    // The vertices lying on each supporting plane, ordered around their centroid.
    std::vector<std::vector<Vec3>> facets;
    const double tolerance = 1e-9 * (1.0 + hull.magnitude());
    for (std::size_t f = 0; f < hull.normals.size(); ++f)
    {
        std::vector<Vec3> facet;
        for (const Vec3 &v : hull.vertices)
            if (std::fabs(hull.normals[f].dot(v) - hull.offsets[f]) <= tolerance)
                facet.push_back(v);
        if (facet.size() < 3)
            continue;
        Vec3 centre = Vec3::Zero();
        for (const Vec3 &v : facet)
            centre += v / double(facet.size());
        const Vec3 n = hull.normals[f];
        const Vec3 u = (facet[0] - centre).normalized(), w = n.cross(u);
        std::sort(facet.begin(), facet.end(), [&](const Vec3 &a, const Vec3 &b) {
            return std::atan2((a - centre).dot(w), (a - centre).dot(u)) <
                   std::atan2((b - centre).dot(w), (b - centre).dot(u));
        });
        facets.push_back(std::move(facet));
    }
    return facets;
}

double hullVolume(const ConvexPiece &hull)
{
    if (hull.dimension < 3)
        return 0.0;
    // Sum of the pyramids from the centroid over every facet fan.
    double volume = 0.0;
    for (const std::vector<Vec3> &facet : facetPolygons(hull))
        for (std::size_t i = 1; i + 1 < facet.size(); ++i)
            volume +=
                std::fabs(
                    (facet[0] - hull.centroid).dot((facet[i] - hull.centroid).cross(facet[i + 1] - hull.centroid))) /
                6.0;
    return volume;
}

double measureConcavity(const ConvexPiece &hull, const TriangleMesh &mesh, const std::vector<std::uint32_t> &triangles,
                        int samplesPerEdge)
{
    double worst = 0.0;
    for (const std::vector<Vec3> &facet : facetPolygons(hull))
    {
        Vec3 centre = Vec3::Zero();
        for (const Vec3 &v : facet)
            centre += v / double(facet.size());
        for (std::size_t i = 0; i < facet.size(); ++i)
        {
            const Vec3 &a = facet[i], &b = facet[(i + 1) % facet.size()];
            for (int s = 0; s <= samplesPerEdge; ++s)
                for (int t = 0; s + t <= samplesPerEdge; ++t)
                {
                    const double bs = double(s) / samplesPerEdge, bt = double(t) / samplesPerEdge;
                    const Vec3 p = centre + bs * (a - centre) + bt * (b - centre);
                    worst = std::max(worst, distanceToTriangles(p, mesh, triangles));
                }
        }
    }
    return worst;
}

namespace
{
// approximationBound's interior grid: this many steps across the hull box's longest side.
constexpr int kGridSteps = 8;

// The hull's axis-aligned box (both corners at the origin for a hull without vertices).
void hullBox(const ConvexPiece &hull, Vec3 &lo, Vec3 &hi)
{
    lo = hi = hull.vertices.empty() ? Vec3::Zero() : hull.vertices.front();
    for (const Vec3 &v : hull.vertices)
    {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
}

// concavitySamplesPerEdge for a hull box of this extent: facet samples at least as dense as the
// interior grid, the box's diagonal over the grid's spacing (8 to 14).
int samplesPerEdgeFor(const Vec3 &extent)
{
    const double longest = extent.maxCoeff();
    // Divided before the norm, so that huge extents cannot overflow; NaN for an unbounded hull.
    const double steps = kGridSteps * (extent / longest).norm();
    if (!(longest > 0.0) || !(steps >= 4.0))
        return 4;
    return steps >= 32.0 ? 32 : int(std::ceil(steps));
}

// A piece's two distances to its triangles: the largest found on its surface (facet samples at least
// as dense as the interior grid of approximationBound) and approximationBound itself.
struct PieceDistances
{
    double surface = 0.0;
    double bound = 0.0;
};

PieceDistances measurePiece(const ConvexPiece &hull, const TriangleMesh &mesh,
                            const std::vector<std::uint32_t> &triangles)
{
    if (triangles.size() == 1)
        return {};  // the hull is the triangle itself
    Vec3 lo, hi;
    hullBox(hull, lo, hi);
    const double spacing = (hi - lo).maxCoeff() / kGridSteps;
    if (!(spacing > 0.0))
        return {};
    PieceDistances d;
    d.surface = measureConcavity(hull, mesh, triangles, samplesPerEdgeFor(hi - lo));
    double worst = d.surface;
    const double slack = 1e-9 * (1.0 + hull.magnitude());
    for (int i = 0; i <= kGridSteps; ++i)
        for (int j = 0; j <= kGridSteps; ++j)
            for (int k = 0; k <= kGridSteps; ++k)
            {
                const Vec3 p = lo + spacing * Vec3(i, j, k);
                if (hull.maxViolation(p) <= slack)
                    worst = std::max(worst, distanceToTriangles(p, mesh, triangles));
            }
    d.bound = worst + spacing;
    return d;
}
}  // namespace

int concavitySamplesPerEdge(const ConvexPiece &hull)
{
    Vec3 lo, hi;
    hullBox(hull, lo, hi);
    return samplesPerEdgeFor(hi - lo);
}

double approximationBound(const ConvexPiece &hull, const TriangleMesh &mesh,
                          const std::vector<std::uint32_t> &triangles)
{
    return measurePiece(hull, mesh, triangles).bound;
}

ConvexDecomposition decomposeClusters(const TriangleMesh &mesh, const std::vector<std::uint32_t> &triangleOrder,
                                      const std::vector<TriangleCluster> &clusters, std::size_t nodeCount)
{
    const auto start = std::chrono::steady_clock::now();
    ConvexDecomposition d;
    d.pieceOfNode.assign(nodeCount, -1);
    std::vector<Vec3> points;
    std::vector<std::uint32_t> triangles;
    for (const TriangleCluster &cluster : clusters)
    {
        points.clear();
        triangles.clear();
        for (std::uint32_t k = 0; k < cluster.count; ++k)
        {
            const std::uint32_t t = triangleOrder[cluster.first + k];
            triangles.push_back(t);
            for (int c = 0; c < 3; ++c)
                points.push_back(mesh.corner(t, c));
        }
        d.pieceOfNode[cluster.node] = std::int32_t(d.pieces.size());
        d.pieces.push_back(ConvexPiece::hullOf(points));
        const PieceDistances distances = measurePiece(d.pieces.back(), mesh, triangles);
        d.concavity.push_back(distances.surface);
        d.approximationBound.push_back(distances.bound);
    }
    d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return d;
}
}  // namespace hcd
