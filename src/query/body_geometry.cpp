// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/body_geometry.h"

#include "hybridcd/geometry/solid_components.h"
#include "hybridcd/narrowphase/shape_pair.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace hcd
{
namespace
{
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kLeafSize = 4;

// One node of the triangle tree: a box (mesh frame, exact min/max of its triangles' corners) and
// either two children or a range of `order`.
struct TreeNode
{
    BoundingBox box;
    int left = -1, right = -1;  // children; -1 for a leaf
    int first = 0, count = 0;   // leaf: triangles order[first, first + count)
};

bool boxesOverlap(const BoundingBox &a, const BoundingBox &b)
{
    return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

// Euclidean distance between boxes (0 when they overlap); boxes may be infinite.
double boxDistance(const BoundingBox &a, const BoundingBox &b)
{
    return boxSeparation(a.min, a.max, b.min, b.max).norm();
}

// Per-context scratch of body queries.
struct BodyScratch
{
    ShapePairScratch pair;
    std::vector<int> stack;
};
}  // namespace

struct BodyGeometry::MeshIndex
{
    std::shared_ptr<const TriangleMesh> mesh;
    std::vector<TreeNode> nodes;  // nodes[0] is the root
    std::vector<std::uint32_t> order;
    SolidQuery solids;

    explicit MeshIndex(std::shared_ptr<const TriangleMesh> m) : mesh(m), solids(m)
    {
        order.resize(mesh->triangleCount());
        std::iota(order.begin(), order.end(), 0u);
        std::vector<Vec3> centroids(mesh->triangleCount());
        for (std::size_t t = 0; t < centroids.size(); ++t)
            centroids[t] = (mesh->corner(t, 0) + mesh->corner(t, 1) + mesh->corner(t, 2)) / 3.0;
        nodes.reserve(2 * order.size() / kLeafSize + 2);
        build(0, static_cast<int>(order.size()), centroids);
    }

    // Median split on the longest axis of the triangles' centroids; returns the node's index.
    int build(int first, int count, const std::vector<Vec3> &centroids)
    {
        const int index = static_cast<int>(nodes.size());
        nodes.emplace_back();
        BoundingBox box, centres;
        for (int i = first; i < first + count; ++i)
        {
            for (int k = 0; k < 3; ++k)
                box.extend(mesh->corner(order[i], k));
            centres.extend(centroids[order[i]]);
        }
        nodes[index].box = box;
        if (count <= kLeafSize)
        {
            nodes[index].first = first;
            nodes[index].count = count;
            return index;
        }
        int axis = 0;
        (centres.max - centres.min).maxCoeff(&axis);
        const int half = count / 2;
        std::nth_element(order.begin() + first, order.begin() + first + half, order.begin() + first + count,
                         [&](std::uint32_t x, std::uint32_t y) { return centroids[x][axis] < centroids[y][axis]; });
        const int left = build(first, half, centroids);
        const int right = build(first + half, count - half, centroids);
        nodes[index].left = left;
        nodes[index].right = right;
        return index;
    }
};

BodyGeometry::BodyGeometry(Shape shape) : shape_(std::move(shape)), radius_(hcd::boundingRadius(shape_))
{
    if (shape_.kind() == ShapeKind::Mesh)
        mesh_ = std::make_shared<const MeshIndex>(shape_.meshPointer());
}

Aabb BodyGeometry::worldBounds(const RigidTransform &worldFromBody) const
{
    Aabb box;
    const BoundingBox b = hcd::worldBounds(shape_, worldFromBody);
    if (!b.min.allFinite() || !b.max.allFinite())
    {
        box.center = Vec3::Zero();
        box.halfExtents = Vec3::Constant(kInfinity);
        return box;
    }
    box.center = 0.5 * (b.min + b.max);
    // Half the width, rounded up by a relative 1e-15 so the box still holds min and max.
    box.halfExtents = 0.5 * (b.max - b.min) * (1.0 + 1e-15) + Vec3::Constant(1e-300);
    box.halfExtents += 1e-15 * box.center.cwiseAbs();
    return box;
}

namespace
{
enum class Mode
{
    Intersect,
    Distance,
    DistanceBound,
};

ShapePairQuery queryOf(Mode mode)
{
    return mode == Mode::Intersect  ? ShapePairQuery::Intersection
           : mode == Mode::Distance ? ShapePairQuery::Distance
                                    : ShapePairQuery::DistanceBound;
}

// A mesh body (meshBody, placed by worldFromMesh) against a non-mesh shape (placed by
// worldFromShape). Points: pointA on the shape, pointB on the mesh (world).
BodyPairResult shapeAgainstMesh(const Shape &shape, const RigidTransform &worldFromShape,
                                const BodyGeometry::MeshIndex &index, const RigidTransform &worldFromMesh, Mode mode,
                                QueryContext &context)
{
    BodyScratch &scratch = context.scratch<BodyScratch>();
    const TriangleMesh &mesh = *index.mesh;
    const RigidTransform meshFromShape = worldFromMesh.inverse() * worldFromShape;
    BodyPairResult result;

    if (shape.kind() == ShapeKind::Halfspace)
    {
        // Exact up to rounding: the lowest vertex along the normal, in the mesh frame.
        const Vec3 n = meshFromShape.rotation * shape.normal();
        const double offset = shape.offset() + n.dot(meshFromShape.translation);
        double lowest = kInfinity;
        Vec3 at = Vec3::Zero();
        for (const Vec3 &v : mesh.vertices)
            if (n.dot(v) < lowest)
            {
                lowest = n.dot(v);
                at = v;
            }
        context.stats.primitiveTests += mesh.vertices.size();
        const double margin =
            1e-12 * (mesh.radiusAboutOrigin() + meshFromShape.translation.norm() + std::abs(shape.offset()));
        const double gap = lowest - offset;
        result.intersecting = !(gap > margin);
        result.distance = result.intersecting ? 0.0 : gap;
        result.pointB = worldFromMesh.apply(at);
        result.pointA = worldFromMesh.apply(at - gap * n);
        return result;
    }

    const BoundingBox shapeBox = hcd::worldBounds(shape, meshFromShape);
    const ShapePairQuery query = queryOf(mode);
    double best = kInfinity;
    std::vector<int> &stack = scratch.stack;
    stack.clear();
    stack.push_back(0);
    while (!stack.empty())
    {
        const TreeNode &node = index.nodes[static_cast<std::size_t>(stack.back())];
        stack.pop_back();
        ++context.stats.boundingVolumeTests;
        if (mode == Mode::Intersect ? !boxesOverlap(node.box, shapeBox) : !(boxDistance(node.box, shapeBox) < best))
            continue;
        if (node.left >= 0)
        {
            stack.push_back(node.left);
            stack.push_back(node.right);
            continue;
        }
        for (int i = node.first; i < node.first + node.count; ++i)
        {
            const std::uint32_t t = index.order[static_cast<std::size_t>(i)];
            ++context.stats.primitiveTests;
            const ShapePairResult r = shapeTriangle(shape, meshFromShape, mesh.corner(t, 0), mesh.corner(t, 1),
                                                    mesh.corner(t, 2), query, scratch.pair);
            if (r.intersecting)
            {
                result.intersecting = true;
                result.distance = 0.0;
                result.pointA = worldFromMesh.apply(r.pointA);
                result.pointB = worldFromMesh.apply(r.pointB);
                return result;
            }
            if (r.distance < best)
            {
                best = r.distance;
                result.pointA = worldFromMesh.apply(r.pointA);
                result.pointB = worldFromMesh.apply(r.pointB);
            }
        }
    }
    // No triangle meets the solid shape: it is wholly inside or wholly outside each closed
    // component, which one point of it decides.
    if (index.solids.closedComponentCount() > 0)
    {
        const Vec3 inside = meshFromShape.apply(supportPoint(shape, Vec3::UnitX()));
        ++context.stats.primitiveTests;
        if (index.solids.insideAnySolid(inside))
        {
            result.intersecting = true;
            result.distance = 0.0;
            result.pointA = result.pointB = worldFromMesh.apply(inside);
            return result;
        }
    }
    result.intersecting = false;
    // Intersect mode gives a positive lower bound only (every triangle test was a separation).
    result.distance = mode != Mode::Intersect ? best : std::numeric_limits<double>::min();
    return result;
}

BodyPairResult bodyPair(const BodyGeometry &a, const RigidTransform &worldFromA, const BodyGeometry &b,
                        const RigidTransform &worldFromB, Mode mode, QueryContext &context)
{
    const bool meshA = a.shape().kind() == ShapeKind::Mesh, meshB = b.shape().kind() == ShapeKind::Mesh;
    if (meshA && meshB)
        throw std::invalid_argument("bodiesIntersect/bodiesDistance: mesh-mesh pairs go to the mesh checkers");
    if (meshB)
        return shapeAgainstMesh(a.shape(), worldFromA, *b.meshIndex(), worldFromB, mode, context);
    if (meshA)
    {
        BodyPairResult r = shapeAgainstMesh(b.shape(), worldFromB, *a.meshIndex(), worldFromA, mode, context);
        std::swap(r.pointA, r.pointB);
        return r;
    }
    BodyScratch &scratch = context.scratch<BodyScratch>();
    ++context.stats.primitiveTests;
    const ShapePairResult r = shapePair(a.shape(), worldFromA, b.shape(), worldFromB, queryOf(mode), scratch.pair);
    BodyPairResult out;
    out.intersecting = r.intersecting;
    out.distance = r.distance;
    out.pointA = r.pointA;
    out.pointB = r.pointB;
    return out;
}
}  // namespace

BodyPairResult bodiesIntersect(const BodyGeometry &a, const RigidTransform &worldFromA, const BodyGeometry &b,
                               const RigidTransform &worldFromB, QueryContext &context)
{
    return bodyPair(a, worldFromA, b, worldFromB, Mode::Intersect, context);
}

const ShapePairScratch &bodyQueryCounters(QueryContext &context) { return context.scratch<BodyScratch>().pair; }

BodyPairResult bodiesDistance(const BodyGeometry &a, const RigidTransform &worldFromA, const BodyGeometry &b,
                              const RigidTransform &worldFromB, QueryContext &context)
{
    return bodyPair(a, worldFromA, b, worldFromB, Mode::Distance, context);
}

BodyPairResult bodiesDistanceBound(const BodyGeometry &a, const RigidTransform &worldFromA, const BodyGeometry &b,
                                   const RigidTransform &worldFromB, QueryContext &context)
{
    return bodyPair(a, worldFromA, b, worldFromB, Mode::DistanceBound, context);
}
}  // namespace hcd
