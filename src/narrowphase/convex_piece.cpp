// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/convex_piece.h"

extern "C"
{
#include <libqhull_r/qhull_ra.h>
}

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <unordered_map>

namespace hcd
{
namespace
{
// Sets thinner than this (relative to their coordinates' magnitude) are treated as flat: Qhull's
// own precision is a few 1e-15 relative, and such slivers are far below the narrow phase's 1e-9.
constexpr double kFlatRelative = 1e-11;

double maxAbsCoordinate(const std::vector<Vec3> &points)
{
    double m = 0.0;
    for (const Vec3 &p : points)
        m = std::max(m, p.cwiseAbs().maxCoeff());
    return m;
}

std::size_t farthestFrom(const std::vector<Vec3> &points, const Vec3 &q)
{
    std::size_t best = 0;
    double bestDistance = -1.0;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        const double d = (points[i] - q).squaredNorm();
        if (d > bestDistance)
            bestDistance = d, best = i;
    }
    return best;
}

// Appends the half-space n.x <= d with d the largest n.p over all input points, so that every
// input point (and so every vertex) satisfies it exactly as evaluated.
void addSupportingHalfspace(ConvexPiece &piece, const Vec3 &normal, const std::vector<Vec3> &points)
{
    double d = -std::numeric_limits<double>::infinity();
    for (const Vec3 &p : points)
        d = std::max(d, normal.dot(p));
    piece.normals.push_back(normal);
    piece.offsets.push_back(d);
}

void finishCentroid(ConvexPiece &piece)
{
    Vec3 sum = Vec3::Zero();
    for (const Vec3 &v : piece.vertices)
        sum += v;
    piece.centroid = sum / double(piece.vertices.size());
}

ConvexPiece pointPiece(const std::vector<Vec3> &points)
{
    ConvexPiece piece;
    piece.dimension = 0;
    for (int axis = 0; axis < 3; ++axis)
    {
        addSupportingHalfspace(piece, Vec3::Unit(axis), points);
        addSupportingHalfspace(piece, -Vec3::Unit(axis), points);
    }
    piece.vertices = {points.front()};
    finishCentroid(piece);
    return piece;
}

ConvexPiece segmentPiece(const std::vector<Vec3> &points, const Vec3 &direction)
{
    ConvexPiece piece;
    piece.dimension = 1;
    const Vec3 u = direction.unitOrthogonal();
    const Vec3 v = direction.cross(u).normalized();
    for (const Vec3 &n : {direction, u, v})
    {
        addSupportingHalfspace(piece, n, points);
        addSupportingHalfspace(piece, -n, points);
    }
    std::size_t lo = 0, hi = 0;
    for (std::size_t i = 1; i < points.size(); ++i)
    {
        if (direction.dot(points[i]) < direction.dot(points[lo]))
            lo = i;
        if (direction.dot(points[i]) > direction.dot(points[hi]))
            hi = i;
    }
    piece.vertices = {points[lo], points[hi]};
    piece.edges = {{0, 1}};
    finishCentroid(piece);
    return piece;
}

// Planar hull: Andrew's monotone chain on coordinates (u, v) within the plane of normal n.
// Returns an empty piece when the projected set turns out collinear.
ConvexPiece planarPiece(const std::vector<Vec3> &points, const Vec3 &n, const Vec3 &u)
{
    const Vec3 v = n.cross(u).normalized();
    const Vec3 origin = points.front();
    std::vector<std::size_t> order(points.size());
    std::vector<Eigen::Vector2d> uv(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        order[i] = i;
        uv[i] = {u.dot(points[i] - origin), v.dot(points[i] - origin)};
    }
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return uv[a].x() < uv[b].x() || (uv[a].x() == uv[b].x() && uv[a].y() < uv[b].y());
    });
    const auto cross = [&](std::size_t o, std::size_t a, std::size_t b) {
        const Eigen::Vector2d oa = uv[a] - uv[o], ob = uv[b] - uv[o];
        return oa.x() * ob.y() - oa.y() * ob.x();
    };
    std::vector<std::size_t> hull(2 * points.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < order.size(); ++i)  // lower chain
    {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], order[i]) <= 0.0)
            --k;
        hull[k++] = order[i];
    }
    for (std::size_t i = order.size() - 1, lower = k + 1; i-- > 0;)  // upper chain
    {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], order[i]) <= 0.0)
            --k;
        hull[k++] = order[i];
    }
    hull.resize(k > 0 ? k - 1 : 0);  // the last point repeats the first
    if (hull.size() < 3)
        return {};

    ConvexPiece piece;
    piece.dimension = 2;
    addSupportingHalfspace(piece, n, points);
    addSupportingHalfspace(piece, -n, points);
    for (std::size_t i = 0; i < hull.size(); ++i)
    {
        const std::size_t j = (i + 1) % hull.size();
        const Eigen::Vector2d e = uv[hull[j]] - uv[hull[i]];
        // Counter-clockwise in (u, v): the outward in-plane normal is the edge turned clockwise.
        const Vec3 outward = (e.y() * u - e.x() * v).normalized();
        addSupportingHalfspace(piece, outward, points);
        piece.vertices.push_back(points[hull[i]]);
        piece.edges.push_back({int(i), int(j)});
    }
    finishCentroid(piece);
    return piece;
}

// /dev/null for Qhull's messages: inputs that reach Qhull are full-dimensional, and a failure is
// handled by the caller, so its diagnostics would only be noise on stderr.
FILE *qhullErrorSink()
{
    static FILE *sink = std::fopen("/dev/null", "w");
    return sink ? sink : stderr;
}

// Full-dimensional hull by Qhull (merged facets, so coplanar triangles become one face).
// Returns an empty piece if Qhull reports an error.
ConvexPiece qhullPiece(const std::vector<Vec3> &points)
{
    std::vector<coordT> coordinates(3 * points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
        for (int c = 0; c < 3; ++c)
            coordinates[3 * i + c] = points[i][c];

    qhT qhStorage;
    qhT *qh = &qhStorage;
    qh_zero(qh, qhullErrorSink());
    char command[] = "qhull";
    const int exitCode =
        qh_new_qhull(qh, 3, int(points.size()), coordinates.data(), False, command, nullptr, qhullErrorSink());
    ConvexPiece piece;
    if (exitCode == 0)
    {
        std::unordered_map<int, int> vertexIndex;  // Qhull point id -> index in piece.vertices
        vertexT *vertex, **vertexp;
        FORALLvertices
        {
            const int id = qh_pointid(qh, vertex->point);
            vertexIndex.emplace(id, int(piece.vertices.size()));
            piece.vertices.push_back(points[std::size_t(id)]);
        }
        facetT *facet, *neighbor, **neighborp;
        FORALLfacets
        {
            const Vec3 normal = Vec3(facet->normal[0], facet->normal[1], facet->normal[2]).normalized();
            if (!normal.allFinite())
                continue;
            addSupportingHalfspace(piece, normal, points);
            // Each edge is the ridge shared by two neighbouring facets: their common vertices,
            // whose two farthest-apart members are the ends (merged facets may keep extra ones).
            FOREACHneighbor_(facet)
            {
                if (neighbor->id < facet->id)
                    continue;
                std::vector<int> common;
                FOREACHvertex_(facet->vertices)
                {
                    if (qh_setin(neighbor->vertices, vertex))
                        common.push_back(vertexIndex.at(qh_pointid(qh, vertex->point)));
                }
                double longest = -1.0;
                std::array<int, 2> edge{-1, -1};
                for (std::size_t i = 0; i < common.size(); ++i)
                    for (std::size_t j = i + 1; j < common.size(); ++j)
                    {
                        const double l = (piece.vertices[common[i]] - piece.vertices[common[j]]).squaredNorm();
                        if (l > longest)
                            longest = l, edge = {common[i], common[j]};
                    }
                if (edge[0] >= 0 && longest > 0.0)
                    piece.edges.push_back(edge);
            }
        }
    }
    qh_freeqhull(qh, !qh_ALL);
    int currentLong = 0, totalLong = 0;
    qh_memfreeshort(qh, &currentLong, &totalLong);
    if (exitCode != 0 || piece.vertices.size() < 4 || piece.normals.size() < 4)
        return {};
    finishCentroid(piece);
    return piece;
}

// Last resort when Qhull fails on a thin but not flat set: the prism over the planar hull, its
// vertices the planar hull's corners lifted onto both caps, so that both descriptions agree.
ConvexPiece prismPiece(const std::vector<Vec3> &points, const Vec3 &n, const Vec3 &u)
{
    ConvexPiece prism = planarPiece(points, n, u);
    if (prism.vertices.empty())
        return prism;
    prism.dimension = 3;
    const double top = prism.offsets[0], bottom = -prism.offsets[1];
    const std::vector<Vec3> base = prism.vertices;
    const int m = int(base.size());
    prism.vertices.clear();
    for (const double level : {bottom, top})
        for (const Vec3 &p : base)
            prism.vertices.push_back(p + (level - n.dot(p)) * n);
    prism.edges.clear();
    for (int i = 0; i < m; ++i)
    {
        prism.edges.push_back({i, (i + 1) % m});
        prism.edges.push_back({m + i, m + (i + 1) % m});
        prism.edges.push_back({i, m + i});
    }
    finishCentroid(prism);
    return prism;
}
}  // namespace

ConvexPiece ConvexPiece::hullOf(const std::vector<Vec3> &points)
{
    if (points.empty())
        throw std::invalid_argument("ConvexPiece::hullOf: no points");
    for (const Vec3 &p : points)
        if (!p.allFinite())
            throw std::invalid_argument("ConvexPiece::hullOf: non-finite point");

    // Affine dimension from successive farthest points: a diameter-like pair, the point farthest
    // from their line, and the point farthest from the plane of the three.
    const double flatTolerance = kFlatRelative * maxAbsCoordinate(points);
    const Vec3 p0 = points[farthestFrom(points, points.front())];
    const Vec3 p1 = points[farthestFrom(points, p0)];
    const double length = (p1 - p0).norm();
    if (!(length > flatTolerance))
        return pointPiece(points);
    const Vec3 direction = (p1 - p0) / length;

    double lineDistance = -1.0;
    Vec3 p2 = p0;
    for (const Vec3 &p : points)
    {
        const Vec3 r = p - p0;
        const double d = (r - direction.dot(r) * direction).norm();
        if (d > lineDistance)
            lineDistance = d, p2 = p;
    }
    if (!(lineDistance > flatTolerance))
        return segmentPiece(points, direction);
    const Vec3 normal = direction.cross(p2 - p0).normalized();

    double planeDistance = 0.0;
    for (const Vec3 &p : points)
        planeDistance = std::max(planeDistance, std::fabs(normal.dot(p - p0)));
    if (!(planeDistance > flatTolerance))
    {
        ConvexPiece flat = planarPiece(points, normal, direction);
        return flat.vertices.empty() ? segmentPiece(points, direction) : flat;
    }

    ConvexPiece solid = qhullPiece(points);
    if (solid.vertices.empty())
        solid = prismPiece(points, normal, direction);
    return solid.vertices.empty() ? segmentPiece(points, direction) : solid;
}

ConvexPiece ConvexPiece::transformed(const RigidTransform &pose) const
{
    ConvexPiece out;
    out.normals.reserve(normals.size());
    out.offsets.reserve(offsets.size());
    for (std::size_t i = 0; i < normals.size(); ++i)
    {
        // n'.(R x + t) = n.x + n'.t, with n' = R n.
        const Vec3 n = pose.rotation * normals[i];
        out.normals.push_back(n);
        out.offsets.push_back(offsets[i] + n.dot(pose.translation));
    }
    out.vertices.reserve(vertices.size());
    for (const Vec3 &v : vertices)
        out.vertices.push_back(pose.apply(v));
    out.edges = edges;
    out.centroid = pose.apply(centroid);
    out.dimension = dimension;
    return out;
}

double ConvexPiece::maxViolation(const Vec3 &p) const
{
    double worst = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < normals.size(); ++i)
        worst = std::max(worst, normals[i].dot(p) - offsets[i]);
    return worst;
}

double ConvexPiece::magnitude() const { return maxAbsCoordinate(vertices); }

VertexGap vertexGapAlong(const Vec3 &direction, const ConvexPiece &a, const ConvexPiece &b)
{
    VertexGap result;
    const double length = direction.norm();
    if (!(length > 0.0) || !std::isfinite(length))
        return result;
    result.normal = direction / length;
    double maxA = -std::numeric_limits<double>::infinity(), minB = std::numeric_limits<double>::infinity();
    for (const Vec3 &v : a.vertices)
        maxA = std::max(maxA, result.normal.dot(v));
    for (const Vec3 &v : b.vertices)
        minB = std::min(minB, result.normal.dot(v));
    result.gap = minB - maxA;
    result.offset = 0.5 * (maxA + minB);  // lies in [maxA, minB] in floating point too
    return result;
}

bool separateAlong(const Vec3 &direction, const ConvexPiece &a, const ConvexPiece &b, double minimumGap, Vec3 &normal,
                   double &offset, double *gap)
{
    const VertexGap along = vertexGapAlong(direction, a, b);
    if (gap)
        *gap = along.gap;
    if (!(along.gap > minimumGap))
        return false;
    normal = along.normal;
    offset = along.offset;
    return true;
}
}  // namespace hcd
