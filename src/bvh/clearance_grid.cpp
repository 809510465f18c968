// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bvh/clearance_grid.h"

#include "hybridcd/geometry/triangle_distance.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace hcd
{
namespace
{
constexpr double kUnreached = 1e20;  // squared distance of a cell no seed reaches
constexpr double kSqrt3 = 1.7320508075688772;

/// Felzenszwalb and Huttenlocher's exact 1D squared distance transform (lower envelope of
/// parabolas), on integer inputs: the envelope breakpoints are rationals with denominators below
/// 2n, so double rounding never changes which parabola is lowest at an integer.
void distanceTransform1d(const double *f, int n, double *d, int *v, double *z)
{
    int k = 0;
    v[0] = 0;
    z[0] = -std::numeric_limits<double>::infinity();
    z[1] = std::numeric_limits<double>::infinity();
    for (int q = 1; q < n; ++q)
    {
        double s = ((f[q] + double(q) * q) - (f[v[k]] + double(v[k]) * v[k])) / (2.0 * q - 2.0 * v[k]);
        while (s <= z[k])
        {
            --k;
            s = ((f[q] + double(q) * q) - (f[v[k]] + double(v[k]) * v[k])) / (2.0 * q - 2.0 * v[k]);
        }
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = std::numeric_limits<double>::infinity();
    }
    k = 0;
    for (int q = 0; q < n; ++q)
    {
        while (z[k + 1] < q)
            ++k;
        d[q] = double(q - v[k]) * (q - v[k]) + f[v[k]];
    }
}

/// In place: squared Euclidean distance (in cells) from each cell centre to the nearest seed
/// (cells holding 0), separably along x, y and z.
void distanceTransform3d(std::vector<double> &grid, int nx, int ny, int nz)
{
    const int longest = std::max({nx, ny, nz});
    std::vector<double> f(longest), d(longest), z(longest + 1);
    std::vector<int> v(longest);
    const auto pass = [&](int n, int countA, int countB, auto index) {
        for (int a = 0; a < countA; ++a)
            for (int b = 0; b < countB; ++b)
            {
                for (int q = 0; q < n; ++q)
                    f[q] = grid[index(q, a, b)];
                distanceTransform1d(f.data(), n, d.data(), v.data(), z.data());
                for (int q = 0; q < n; ++q)
                    grid[index(q, a, b)] = std::min(d[q], kUnreached);
            }
    };
    const auto at = [nx, ny](int x, int y, int z) { return (std::size_t(z) * ny + y) * nx + x; };
    pass(nx, ny, nz, [&](int q, int a, int b) { return at(q, a, b); });
    pass(ny, nx, nz, [&](int q, int a, int b) { return at(a, q, b); });
    pass(nz, nx, ny, [&](int q, int a, int b) { return at(a, b, q); });
}

/// The distance from a point of a cell to any point of a seed cell whose centres are
/// sqrt(squared) cells apart, in whole units of 1 / unitsPerCell cells, rounded down: the query
/// point may be `queryOffset` cells off its cell's centre, the seed's points half a cell diagonal.
int unitsBelow(double squared, double queryOffset, int unitsPerCell, int saturate)
{
    if (squared >= kUnreached)
        return saturate;
    const double units = std::floor(unitsPerCell * (std::sqrt(squared) - queryOffset - 0.5 * kSqrt3) - 1e-9);
    return units <= 0.0 ? 0 : int(std::min<double>(units, saturate));
}
}  // namespace

ClearanceGrid::ClearanceGrid(const TriangleMesh &mesh, const SolidQuery *solids, const std::vector<Vec3> &markers,
                             ClearanceGridSettings settings)
{
    if (mesh.empty())
        return;
    const auto start = std::chrono::steady_clock::now();
    BoundingBox box = mesh.bounds();
    const bool planar = settings.planar;
    if (planar)
        box.min.z() = box.max.z() = 0.0;  // the triangles' shadows on z = 0
    meshMin_ = box.min;
    meshMax_ = box.max;
    const double margin = std::max(0.0, settings.margin);
    const Vec3 extent = (box.max - box.min).array() + 2.0 * margin;
    const double magnitude = std::max(box.min.cwiseAbs().maxCoeff(), box.max.cwiseAbs().maxCoeff()) + extent.maxCoeff();
    // Cubic cells; a flat mesh still gets one layer of cells across its thin side.
    const double floorExtent = std::max(extent.maxCoeff() * 1e-3, 1e-300);
    const Vec3 padded = extent.cwiseMax(Vec3::Constant(floorExtent));
    const std::size_t maxCells = std::max<std::size_t>(settings.maxCells, 8);
    const auto countOf = [&](double size, double cell) { return std::max(1, int(std::ceil(size / cell))); };
    // Planar: square cells over x and y, one layer centred on z = 0.
    double h =
        planar ? std::sqrt(padded.x() * padded.y() / double(maxCells)) : std::cbrt(padded.prod() / double(maxCells));
    const auto layers = [&](double cell) { return planar ? 1 : countOf(padded.z(), cell); };
    while (double(countOf(padded.x(), h)) * countOf(padded.y(), h) * layers(h) > double(maxCells))
        h *= 1.05;
    cellSize_ = h;
    inverseCellSize_ = 1.0 / h;
    nx_ = countOf(padded.x(), h);
    ny_ = countOf(padded.y(), h);
    nz_ = layers(h);
    origin_ = box.min.array() - margin;
    if (planar)
        origin_.z() = -0.5 * h;
    roundingSlack_ = 1e-9 * magnitude;
    const std::size_t cellCount = std::size_t(nx_) * ny_ * nz_;
    const auto cellIndex = [&](int x, int y, int z) { return (std::size_t(z) * ny_ + y) * nx_ + x; };
    const auto cellRange = [&](double lo, double hi, int axis, int count, int &first, int &last) {
        first = std::clamp(int(std::floor((lo - origin_[axis]) * inverseCellSize_)), 0, count - 1);
        last = std::clamp(int(std::floor((hi - origin_[axis]) * inverseCellSize_)), 0, count - 1);
    };

    // Occupied cells: the triangle's bounding box, grown for rounding, cut by a slab around its
    // plane as wide as the cell's projection on the normal. Marks a superset of touched cells.
    std::vector<double> squared(cellCount, kUnreached);
    std::vector<std::uint32_t> firstTriangle(settings.keepTriangles ? cellCount : 0, ~0u);
    const double boxSlack = 1e-9 * magnitude;
    const auto shadow = [planar](const Vec3 &v) { return planar ? Vec3(v.x(), v.y(), 0.0) : v; };
    // Planar: a cell is occupied when the shadow comes within its half diagonal of the centre
    // (shadows of upright faces are segments, which a slab test would not narrow down).
    const double planarReach = 0.5 * kSqrt3 * h * (1.0 + 1e-9) + boxSlack;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
        const Vec3 a = shadow(mesh.corner(t, 0)), b = shadow(mesh.corner(t, 1)), c = shadow(mesh.corner(t, 2));
        const Vec3 lo = a.cwiseMin(b).cwiseMin(c).array() - boxSlack;
        const Vec3 hi = a.cwiseMax(b).cwiseMax(c).array() + boxSlack;
        int x0, x1, y0, y1, z0, z1;
        cellRange(lo.x(), hi.x(), 0, nx_, x0, x1);
        cellRange(lo.y(), hi.y(), 1, ny_, y0, y1);
        cellRange(lo.z(), hi.z(), 2, nz_, z0, z1);
        const Vec3 normal = (b - a).cross(c - a);
        const double normalSum = normal.cwiseAbs().sum();
        const double reach = 0.5 * h * normalSum + 1e-9 * normalSum * (magnitude + h);
        for (int z = z0; z <= z1; ++z)
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x)
                {
                    const Vec3 centre = origin_ + h * Vec3(x + 0.5, y + 0.5, z + 0.5);
                    if (planar ? (closestPointOnTriangle(centre, a, b, c) - centre).norm() <= planarReach
                               : std::abs(normal.dot(centre - a)) <= reach)
                    {
                        const std::size_t i = cellIndex(x, y, z);
                        squared[i] = 0.0;
                        if (settings.keepTriangles && firstTriangle[i] == ~0u)
                            firstTriangle[i] = std::uint32_t(t);
                    }
                }
    }
    std::vector<std::uint8_t> freeCell(cellCount);
    for (std::size_t i = 0; i < cellCount; ++i)
    {
        freeCell[i] = squared[i] != 0.0;
        occupied_ += !freeCell[i];
    }
    if (settings.keepTriangles)
    {
        occupiedMask_.assign((cellCount + 63) / 64, 0);
        occupiedBefore_.assign(occupiedMask_.size(), 0);
        std::uint32_t count = 0;
        for (std::size_t i = 0; i < cellCount; ++i)
        {
            if (i % 64 == 0)
                occupiedBefore_[i / 64] = count;
            if (!freeCell[i])
            {
                occupiedMask_[i / 64] |= std::uint64_t(1) << (i % 64);
                occupiedTriangle_.push_back(firstTriangle[i]);
                ++count;
            }
        }
    }
    distanceTransform3d(squared, nx_, ny_, nz_);

    // Sides: one exact point-in-solid test per face-connected region of free cells.
    std::vector<std::uint8_t> insideCell(cellCount, 0);
    labelled_ = solids != nullptr && !planar;
    if (labelled_ && solids->closedComponentCount() > 0)
    {
        std::vector<std::uint8_t> seen(cellCount, 0);
        std::vector<std::size_t> queue;
        for (std::size_t seed = 0; seed < cellCount; ++seed)
        {
            if (!freeCell[seed] || seen[seed])
                continue;
            const int sx = int(seed % nx_), sy = int((seed / nx_) % ny_), sz = int(seed / (std::size_t(nx_) * ny_));
            const bool inside = solids->insideAnySolid(origin_ + h * Vec3(sx + 0.5, sy + 0.5, sz + 0.5));
            queue.assign(1, seed);
            seen[seed] = 1;
            while (!queue.empty())
            {
                const std::size_t i = queue.back();
                queue.pop_back();
                insideCell[i] = inside;
                const int x = int(i % nx_), y = int((i / nx_) % ny_), z = int(i / (std::size_t(nx_) * ny_));
                const int neighbours[6][3] = {{x - 1, y, z}, {x + 1, y, z}, {x, y - 1, z},
                                              {x, y + 1, z}, {x, y, z - 1}, {x, y, z + 1}};
                for (const auto &n : neighbours)
                {
                    if (n[0] < 0 || n[1] < 0 || n[2] < 0 || n[0] >= nx_ || n[1] >= ny_ || n[2] >= nz_)
                        continue;
                    const std::size_t j = cellIndex(n[0], n[1], n[2]);
                    if (freeCell[j] && !seen[j])
                    {
                        seen[j] = 1;
                        queue.push_back(j);
                    }
                }
            }
        }
    }
    hasMarkers_ = !markers.empty() && !planar;
    cellBytes_.resize(cellCount);
    for (std::size_t i = 0; i < cellCount; ++i)
        cellBytes_[i] = !freeCell[i]    ? 0
                        : insideCell[i] ? std::uint8_t(128 + unitsBelow(squared[i], 0.0, 2, 127))
                                        : std::uint8_t(1 + unitsBelow(squared[i], 0.0, 2, 126));

    if (hasMarkers_)
    {
        std::fill(squared.begin(), squared.end(), kUnreached);
        for (const Vec3 &m : markers)
        {
            int x0, x1, y0, y1, z0, z1;
            cellRange(m.x() - boxSlack, m.x() + boxSlack, 0, nx_, x0, x1);
            cellRange(m.y() - boxSlack, m.y() + boxSlack, 1, ny_, y0, y1);
            cellRange(m.z() - boxSlack, m.z() + boxSlack, 2, nz_, z0, z1);
            for (int z = z0; z <= z1; ++z)
                for (int y = y0; y <= y1; ++y)
                    for (int x = x0; x <= x1; ++x)
                        squared[cellIndex(x, y, z)] = 0.0;
        }
        distanceTransform3d(squared, nx_, ny_, nz_);
        markerBytes_.resize(cellCount);
        for (std::size_t i = 0; i < cellCount; ++i)
            markerBytes_[i] = std::uint8_t(unitsBelow(squared[i], 0.5 * kSqrt3, 1, 255));
    }
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::int64_t ClearanceGrid::triangleNear(const Vec3 &p) const
{
    if (occupiedMask_.empty())
        return -1;
    const CellPoint cell = locate(p);
    if (!cell.inGrid)
        return -1;
    const std::size_t i = cell.index;
    const std::uint64_t word = occupiedMask_[i / 64];
    const std::uint64_t bit = std::uint64_t(1) << (i % 64);
    if (!(word & bit))
        return -1;
    return occupiedTriangle_[occupiedBefore_[i / 64] + std::size_t(__builtin_popcountll(word & (bit - 1)))];
}

}  // namespace hcd
