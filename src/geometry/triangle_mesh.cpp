// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/geometry/triangle_mesh.h"

#include "hybridcd/geometry/triangle_intersection.h"

#include <algorithm>
#include <map>
#include <tuple>

namespace hcd
{
using Triangle = TriangleMesh::Triangle;

BoundingBox TriangleMesh::bounds() const
{
    BoundingBox box;
    for (const Triangle &t : triangles)
        for (std::uint32_t v : t)
            box.extend(vertices[v]);
    return box;
}

double TriangleMesh::radiusAboutOrigin() const
{
    double r = 0.0;
    for (const Vec3 &v : vertices)
        r = std::max(r, v.norm());
    return r;
}

double TriangleMesh::radiusAboutZAxis() const
{
    double r = 0.0;
    for (const Vec3 &v : vertices)
        r = std::max(r, v.head<2>().norm());
    return r;
}

std::size_t TriangleMesh::memoryBytes() const
{
    return vertices.capacity() * sizeof(Vec3) + triangles.capacity() * sizeof(Triangle);
}

bool isClosed(const TriangleMesh &mesh)
{
    if (mesh.empty())
        return false;
    // Canonical (sorted) corner triple identifies a face regardless of orientation.
    std::vector<Triangle> faces;
    faces.reserve(mesh.triangles.size());
    for (Triangle t : mesh.triangles)
    {
        std::sort(t.begin(), t.end());
        faces.push_back(t);
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());

    return everyEdgeUsedEvenly(faces);
}

bool everyEdgeUsedEvenly(const std::vector<Triangle> &sortedFaces)
{
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    edges.reserve(sortedFaces.size() * 3);
    for (const Triangle &f : sortedFaces)
    {
        edges.emplace_back(f[0], f[1]);
        edges.emplace_back(f[1], f[2]);
        edges.emplace_back(f[0], f[2]);
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();)
    {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i])
            ++j;
        if ((j - i) % 2 != 0)
            return false;
        i = j;
    }
    return !edges.empty();
}

std::size_t weldAndDropDegenerate(TriangleMesh &mesh)
{
    std::map<std::tuple<double, double, double>, std::uint32_t> index;
    std::vector<Vec3> welded;
    std::vector<std::uint32_t> remap(mesh.vertices.size());
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    {
        const Vec3 &v = mesh.vertices[i];
        auto [it, inserted] = index.emplace(std::make_tuple(v.x(), v.y(), v.z()), std::uint32_t(welded.size()));
        if (inserted)
            welded.push_back(v);
        remap[i] = it->second;
    }

    std::vector<Triangle> kept;
    kept.reserve(mesh.triangles.size());
    for (const Triangle &t : mesh.triangles)
    {
        const Triangle r{remap[t[0]], remap[t[1]], remap[t[2]]};
        if (r[0] == r[1] || r[1] == r[2] || r[0] == r[2] ||
            isDegenerateTriangle(welded[r[0]], welded[r[1]], welded[r[2]]))
            continue;
        kept.push_back(r);
    }
    const std::size_t dropped = mesh.triangles.size() - kept.size();
    mesh.vertices = std::move(welded);
    mesh.triangles = std::move(kept);
    return dropped;
}

DistinctFaceMesh withoutRepeatedFaces(std::shared_ptr<const TriangleMesh> mesh)
{
    DistinctFaceMesh out;
    if (!mesh)
        return out;
    // Sort (sorted corners, index) pairs: each group of repeats is contiguous, its first index first.
    const std::vector<Triangle> &triangles = mesh->triangles;
    std::vector<std::pair<Triangle, std::uint32_t>> keys;
    keys.reserve(triangles.size());
    for (std::uint32_t t = 0; t < triangles.size(); ++t)
    {
        Triangle key = triangles[t];
        std::sort(key.begin(), key.end());
        keys.emplace_back(key, t);
    }
    std::sort(keys.begin(), keys.end());
    std::vector<char> keep(triangles.size(), 0);
    for (std::size_t i = 0; i < keys.size(); ++i)
        keep[keys[i].second] = i == 0 || keys[i].first != keys[i - 1].first;
    const std::size_t kept = std::size_t(std::count(keep.begin(), keep.end(), char(1)));
    if (kept == triangles.size())
    {
        out.mesh = std::move(mesh);
        return out;
    }
    auto distinct = std::make_shared<TriangleMesh>();
    distinct->vertices = mesh->vertices;
    distinct->triangles.reserve(kept);
    out.sourceTriangle.reserve(kept);
    for (std::uint32_t t = 0; t < triangles.size(); ++t)
        if (keep[t])
        {
            distinct->triangles.push_back(triangles[t]);
            out.sourceTriangle.push_back(t);
        }
    out.dropped = triangles.size() - kept;
    out.mesh = std::move(distinct);
    return out;
}
}  // namespace hcd
