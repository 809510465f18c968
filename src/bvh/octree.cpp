// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bvh/octree.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace hcd
{
namespace
{
// Whether the projections of the (cube-centred) corners on `axis` miss [-r, r] by more than the
// tolerance scaled to the axis' length (the axes are not normalised).
bool separates(const Vec3 &axis, const Vec3 &v0, const Vec3 &v1, const Vec3 &v2, double halfSide, double tolerance)
{
    const double p0 = axis.dot(v0), p1 = axis.dot(v1), p2 = axis.dot(v2);
    const double r = halfSide * axis.cwiseAbs().sum();
    const double slack = tolerance * axis.norm();
    return std::min({p0, p1, p2}) > r + slack || std::max({p0, p1, p2}) < -r - slack;
}
}  // namespace

bool triangleTouchesCube(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &center, double halfSide,
                         double tolerance)
{
    const Vec3 v0 = a - center, v1 = b - center, v2 = c - center;
    // The cube's faces: the triangle's bounds against the cube's.
    const Vec3 lo = v0.cwiseMin(v1).cwiseMin(v2), hi = v0.cwiseMax(v1).cwiseMax(v2);
    if ((lo.array() > halfSide + tolerance).any() || (hi.array() < -halfSide - tolerance).any())
        return false;
    const Vec3 edges[3] = {v1 - v0, v2 - v1, v0 - v2};
    if (separates(edges[0].cross(edges[1]), v0, v1, v2, halfSide, tolerance))
        return false;
    for (const Vec3 &e : edges)
        for (int k = 0; k < 3; ++k)
            if (separates(Vec3::Unit(k).cross(e), v0, v1, v2, halfSide, tolerance))
                return false;
    return true;
}

Octree::Octree(std::shared_ptr<const TriangleMesh> mesh, Limits limits) : mesh_(std::move(mesh)), limits_(limits)
{
    const auto start = std::chrono::steady_clock::now();
    const std::size_t n = mesh_->triangleCount();
    if (n == 0)
        return;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::size_t t = 0; t < n; ++t)
        for (int k = 0; k < 3; ++k)
        {
            lo = lo.cwiseMin(mesh_->corner(t, k));
            hi = hi.cwiseMax(mesh_->corner(t, k));
        }
    const double magnitude = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    // Rounding in the separating-axis sums is far below 1e-9 of the coordinates' magnitude.
    tolerance_ = 1e-9 * magnitude + 1e-300;
    Cell root;
    root.center = 0.5 * (lo + hi);
    root.halfSide = 0.5 * (hi - lo).maxCoeff() * (1.0 + 1e-9) + tolerance_;
    cells_.push_back(root);
    std::vector<std::uint32_t> all(n);
    for (std::size_t t = 0; t < n; ++t)
        all[t] = std::uint32_t(t);
    build(0, std::move(all), 0);
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void Octree::makeLeaf(std::uint32_t cell, const std::vector<std::uint32_t> &triangles)
{
    Cell &leaf = cells_[cell];
    leaf.firstTriangle = std::uint32_t(references_.size());
    leaf.triangleCount = std::uint32_t(triangles.size());
    references_.insert(references_.end(), triangles.begin(), triangles.end());
    ++leaves_;
}

void Octree::build(std::uint32_t cell, std::vector<std::uint32_t> triangles, std::size_t level)
{
    depth_ = std::max(depth_, level + 1);
    if (triangles.size() <= limits_.leafTriangles || level >= limits_.maxDepth)
        return makeLeaf(cell, triangles);
    // Sort the triangles into the eight octants; keep the octants that hold any.
    const Vec3 center = cells_[cell].center;
    const double half = 0.5 * cells_[cell].halfSide;
    std::vector<std::pair<Vec3, std::vector<std::uint32_t>>> children;
    for (int octant = 0; octant < 8; ++octant)
    {
        const Vec3 c = center + half * Vec3(octant & 1 ? 1 : -1, octant & 2 ? 1 : -1, octant & 4 ? 1 : -1);
        std::vector<std::uint32_t> inside;
        for (const std::uint32_t t : triangles)
            if (triangleTouchesCube(mesh_->corner(t, 0), mesh_->corner(t, 1), mesh_->corner(t, 2), c, half, tolerance_))
                inside.push_back(t);
        if (!inside.empty())
            children.emplace_back(c, std::move(inside));
    }
    // Where triangles meet at a vertex or run along an edge, splitting stops paying: when one
    // octant still holds all of the cell's triangles, the cell stays a leaf.
    const bool stuck = std::any_of(children.begin(), children.end(),
                                   [&](const auto &child) { return child.second.size() == triangles.size(); });
    // A bound on memory whatever the mesh: the octants may list a triangle many times over, and
    // past 32 listings per triangle on average, cells are no longer split.
    std::size_t listings = 0;
    for (const auto &child : children)
        listings += child.second.size();
    if (stuck || listed_ + listings > 32 * mesh_->triangleCount())
        return makeLeaf(cell, triangles);
    listed_ += listings;
    triangles.clear();
    triangles.shrink_to_fit();
    const std::uint32_t first = std::uint32_t(cells_.size());
    cells_[cell].firstChild = std::int32_t(first);
    cells_[cell].childCount = std::uint32_t(children.size());
    for (const auto &child : children)
    {
        Cell c;
        c.center = child.first;
        c.halfSide = half;
        cells_.push_back(c);
    }
    for (std::size_t k = 0; k < children.size(); ++k)
        build(first + std::uint32_t(k), std::move(children[k].second), level + 1);
}
}  // namespace hcd
