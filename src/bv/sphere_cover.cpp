// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bv/sphere_cover.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace hcd
{
namespace
{
using Piece = std::array<Vec3, 3>;

/// The triangle cut into n * n congruent pieces (n = pieces per edge).
void cutInto(const Vec3 &a, const Vec3 &b, const Vec3 &c, int n, std::vector<Piece> &out)
{
    const auto at = [&](int i, int j) { return a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j)
        {
            out.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
            if (i + j + 1 < n)
                out.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        }
}

CoverSphere sphereOf(const std::vector<Piece> &pieces, std::size_t first, std::size_t last)
{
    BoundingBox box;
    for (std::size_t p = first; p < last; ++p)
        for (const Vec3 &v : pieces[p])
            box.extend(v);
    CoverSphere s;
    s.center = 0.5 * (box.min + box.max);
    double squared = 0.0;
    for (std::size_t p = first; p < last; ++p)
        for (const Vec3 &v : pieces[p])
            squared = std::max(squared, (v - s.center).squaredNorm());
    // Outward rounding: the cut corners and the distances carry a few ulps of the coordinates.
    s.radius =
        std::sqrt(squared) * (1.0 + 1e-12) + 1e-12 * (box.min.cwiseAbs().maxCoeff() + box.max.cwiseAbs().maxCoeff());
    s.probe = pieces[first][0];
    return s;
}
}  // namespace

std::vector<CoverSphere> sphereCover(const TriangleMesh &mesh, std::size_t maxLeaves)
{
    if (mesh.empty() || maxLeaves == 0)
        return {};
    const BoundingBox box = mesh.bounds();
    const double longest = std::max((box.max - box.min).maxCoeff() / 8.0, 1e-300);
    std::vector<Piece> pieces;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
        const Vec3 &a = mesh.corner(t, 0), &b = mesh.corner(t, 1), &c = mesh.corner(t, 2);
        const double edge = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
        const int n = int(std::clamp(std::ceil(edge / longest), 1.0, 16.0));
        if (n == 1)
            pieces.push_back({a, b, c});  // the corners themselves, bit for bit
        else
            cutInto(a, b, c, n, pieces);
    }
    // Cut corners may sit a few ulps off their triangle; the radii's outward rounding covers that.

    struct Range
    {
        std::size_t first, last, node;
    };
    std::vector<CoverSphere> nodes{sphereOf(pieces, 0, pieces.size())};
    std::vector<Range> open{{0, pieces.size(), 0}};
    std::size_t leaves = 1;
    while (leaves < maxLeaves && !open.empty())
    {
        // Split the open node with the largest sphere.
        std::size_t pick = 0;
        for (std::size_t i = 1; i < open.size(); ++i)
            if (nodes[open[i].node].radius > nodes[open[pick].node].radius)
                pick = i;
        const Range r = open[pick];
        open.erase(open.begin() + std::ptrdiff_t(pick));
        if (r.last - r.first < 2)
            continue;
        const auto centroid = [](const Piece &p) { return (p[0] + p[1] + p[2]) / 3.0; };
        BoundingBox centres;
        for (std::size_t p = r.first; p < r.last; ++p)
            centres.extend(centroid(pieces[p]));
        int axis = 0;
        (centres.max - centres.min).maxCoeff(&axis);
        const std::size_t middle = r.first + (r.last - r.first) / 2;
        std::nth_element(pieces.begin() + std::ptrdiff_t(r.first), pieces.begin() + std::ptrdiff_t(middle),
                         pieces.begin() + std::ptrdiff_t(r.last),
                         [&](const Piece &a, const Piece &b) { return centroid(a)[axis] < centroid(b)[axis]; });
        const std::size_t child = nodes.size();
        nodes[r.node].firstChild = int(child);
        nodes.push_back(sphereOf(pieces, r.first, middle));
        nodes.push_back(sphereOf(pieces, middle, r.last));
        open.push_back({r.first, middle, child});
        open.push_back({middle, r.last, child + 1});
        ++leaves;
    }
    return nodes;
}
}  // namespace hcd
