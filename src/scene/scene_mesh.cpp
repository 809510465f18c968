// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/scene/scene_mesh.h"

#include "hybridcd/narrowphase/convex_decomposition.h"
#include "hybridcd/narrowphase/convex_piece.h"

#include <cmath>

namespace hcd
{
namespace
{
// Appends the hull of `points` (world frame) as triangles, fanned from each facet's first corner.
void appendHull(TriangleMesh &mesh, const std::vector<Vec3> &points)
{
    if (points.size() < 3)
        return;
    const ConvexPiece hull = ConvexPiece::hullOf(points);
    if (hull.dimension < 2)
        return;
    for (const std::vector<Vec3> &facet : facetPolygons(hull))
    {
        if (facet.size() < 3)
            continue;
        const auto first = std::uint32_t(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), facet.begin(), facet.end());
        for (std::uint32_t k = 1; k + 1 < facet.size(); ++k)
            mesh.triangles.push_back({first, first + k, first + k + 1});
    }
}

void appendMesh(TriangleMesh &mesh, const TriangleMesh &part, const RigidTransform &worldFromPart)
{
    const auto first = std::uint32_t(mesh.vertices.size());
    for (const Vec3 &v : part.vertices)
        mesh.vertices.push_back(worldFromPart.apply(v));
    for (const auto &t : part.triangles)
        mesh.triangles.push_back({first + t[0], first + t[1], first + t[2]});
}

// The corners of `clip` inside the half-space and the points where its edges cross the plane.
std::vector<Vec3> clippedHalfspace(const Vec3 &normal, double offset, const BoundingBox &clip)
{
    std::vector<Vec3> corners, points;
    for (int i = 0; i < 8; ++i)
        corners.push_back(Vec3(i & 1 ? clip.max.x() : clip.min.x(), i & 2 ? clip.max.y() : clip.min.y(),
                               i & 4 ? clip.max.z() : clip.min.z()));
    for (const Vec3 &c : corners)
        if (normal.dot(c) <= offset)
            points.push_back(c);
    for (int i = 0; i < 8; ++i)
        for (int axis = 0; axis < 3; ++axis)
        {
            const int j = i | (1 << axis);
            if (j == i)
                continue;
            const double a = normal.dot(corners[std::size_t(i)]) - offset,
                         b = normal.dot(corners[std::size_t(j)]) - offset;
            if ((a < 0.0) != (b < 0.0))
                points.push_back(corners[std::size_t(i)] +
                                 (a / (a - b)) * (corners[std::size_t(j)] - corners[std::size_t(i)]));
        }
    return points;
}
}  // namespace

TriangleMesh bodyMesh(const SceneBody &body, const BoundingBox &clip, int resolution)
{
    const Shape &shape = body.geometry->shape();
    TriangleMesh mesh;
    switch (shape.kind())
    {
    case ShapeKind::Mesh:
        appendMesh(mesh, *shape.meshPointer(), RigidTransform());
        break;
    case ShapeKind::Halfspace:
    {
        // In the world frame directly: the owner pose is the static body's world pose.
        const Vec3 normal = body.ownerFromBody.rotation * shape.normal();
        const double offset = shape.offset() + normal.dot(body.ownerFromBody.translation);
        if (!clip.empty())
            appendHull(mesh, clippedHalfspace(normal, offset, clip));
        break;
    }
    default:
        appendHull(mesh, tessellationPoints(shape, resolution, TessellationSide::Inner));
        break;
    }
    return mesh;
}

TriangleMesh staticBodiesMesh(const Scene &scene, const BoundingBox &clip, int resolution)
{
    TriangleMesh mesh;
    for (const SceneBody &body : scene.bodies())
    {
        if (body.robot >= 0)
            continue;
        const bool world = body.geometry->shape().kind() == ShapeKind::Halfspace;
        appendMesh(mesh, bodyMesh(body, clip, resolution), world ? RigidTransform() : body.ownerFromBody);
    }
    return mesh;
}

TriangleMesh robotBodiesMesh(const Scene &scene, const RigidTransform *worldFromRobot, int resolution)
{
    TriangleMesh mesh;
    for (std::size_t i = 0; i < scene.bodies().size(); ++i)
        if (scene.bodies()[i].robot >= 0)
            appendMesh(mesh, bodyMesh(scene.bodies()[i], BoundingBox(), resolution),
                       scene.worldFromBody(i, worldFromRobot));
    return mesh;
}

BoundingBox sceneClipBox(const Scene &scene, const std::vector<std::vector<RigidTransform>> &poses)
{
    BoundingBox box;
    for (const SceneBody &body : scene.bodies())
    {
        if (body.robot >= 0)
            continue;
        const BoundingBox b = worldBounds(body.geometry->shape(), body.ownerFromBody);
        if (b.min.allFinite() && b.max.allFinite())
        {
            box.extend(b.min);
            box.extend(b.max);
        }
    }
    for (const std::vector<RigidTransform> &state : poses)
        for (std::size_t i = 0; i < scene.bodies().size(); ++i)
            if (scene.bodies()[i].robot >= 0)
            {
                const BoundingBox b =
                    worldBounds(scene.bodies()[i].geometry->shape(), scene.worldFromBody(i, state.data()));
                box.extend(b.min);
                box.extend(b.max);
            }
    if (box.empty())
        return box;
    const double grow = 0.1 * (box.max - box.min).norm();
    box.min -= Vec3::Constant(grow);
    box.max += Vec3::Constant(grow);
    return box;
}
}  // namespace hcd
