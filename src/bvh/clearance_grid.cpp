// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bvh/clearance_grid.h"

#include "hybridcd/bvh/distance_transform.h"
#include "hybridcd/bvh/grid_regions.h"
#include "hybridcd/geometry/triangle_distance.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

namespace hcd
{
namespace
{
constexpr double kSqrt3 = 1.7320508075688772;

/// The distance from a point of a cell to any point of a seed cell whose centres are
/// sqrt(squared) cells apart, in whole units of 1 / unitsPerCell cells, rounded down: the query
/// point may be `queryOffset` cells off its cell's centre, the seed's points half a cell diagonal.
int unitsBelow(double squared, double queryOffset, int unitsPerCell, int saturate)
{
    const double units = std::floor(unitsPerCell * (std::sqrt(squared) - queryOffset - 0.5 * kSqrt3) - 1e-9);
    return units <= 0.0 ? 0 : int(std::min<double>(units, saturate));
}
/// The squared distance in the plane z = 0 from p to the triangle abc (their x and y), in units of
/// `unit` (a cell: every value stays near the grid's size in cells, far from overflow or
/// underflow at any scale): zero inside, else the nearest of its three edges. A triangle seen edge
/// on (an upright face's shadow) is its edges alone.
double squaredShadowDistance(const Vec3 &p, const Vec3 &a, const Vec3 &b, const Vec3 &c, double inverseUnit)
{
    const double ax = (a.x() - p.x()) * inverseUnit, ay = (a.y() - p.y()) * inverseUnit;
    const double bx = (b.x() - p.x()) * inverseUnit, by = (b.y() - p.y()) * inverseUnit;
    const double cx = (c.x() - p.x()) * inverseUnit, cy = (c.y() - p.y()) * inverseUnit;
    // Where p (the origin now) lies against each edge.
    const double ab = ax * by - ay * bx, bc = bx * cy - by * cx, ca = cx * ay - cy * ax;
    if ((ab > 0.0 && bc > 0.0 && ca > 0.0) || (ab < 0.0 && bc < 0.0 && ca < 0.0))
        return 0.0;
    const auto toSegment = [](double ux, double uy, double vx, double vy) {
        const double ex = vx - ux, ey = vy - uy;
        const double length = ex * ex + ey * ey;
        const double t = length > 0.0 ? std::clamp(-(ux * ex + uy * ey) / length, 0.0, 1.0) : 0.0;
        const double dx = ux + t * ex, dy = uy + t * ey;
        return dx * dx + dy * dy;
    };
    return std::min({toSegment(ax, ay, bx, by), toSegment(bx, by, cx, cy), toSegment(cx, cy, ax, ay)});
}
/// The x extent [xl, xr] of the part of triangle abc (its x and y) with y in [yLow, yHigh]; false
/// when no part of it is. The part is convex: its extremes are corners in the strip or crossings
/// of the edges with the strip's two lines.
bool shadowExtentInStrip(const Vec3 &a, const Vec3 &b, const Vec3 &c, double yLow, double yHigh, double &xl, double &xr)
{
    xl = std::numeric_limits<double>::infinity();
    xr = -xl;
    const auto take = [&](double x) {
        xl = std::min(xl, x);
        xr = std::max(xr, x);
    };
    const Vec3 *corners[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k)
    {
        const Vec3 &u = *corners[k], &v = *corners[(k + 1) % 3];
        if (u.y() >= yLow && u.y() <= yHigh)
            take(u.x());
        for (double line : {yLow, yHigh})
            if ((u.y() < line) != (v.y() < line))
                take(u.x() + (v.x() - u.x()) * ((line - u.y()) / (v.y() - u.y())));
    }
    return xl <= xr;
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
    // At most 2^31 cells: cells and occupied cells are counted in 32 bits.
    const std::size_t maxCells = std::clamp<std::size_t>(settings.maxCells, 8, std::size_t(1) << 31);
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
    std::vector<std::uint8_t> occupiedCell(cellCount, 0);
    // (cell, triangle) for each cell as it becomes occupied: the first triangle that marked it.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> firstMarks;
    const double boxSlack = 1e-9 * magnitude;
    const auto shadow = [planar](const Vec3 &v) { return planar ? Vec3(v.x(), v.y(), 0.0) : v; };
    // Planar: a cell is occupied when the shadow comes within its half diagonal of the centre
    // (shadows of upright faces are segments, which a slab test would not narrow down).
    const double planarReach = 0.5 * kSqrt3 * h * (1.0 + 1e-9) + boxSlack;
    // Its square in cells, as squaredShadowDistance measures.
    const double planarReachCells = (planarReach * inverseCellSize_) * (planarReach * inverseCellSize_);
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
            {
                int first = x0, last = x1;
                if (planar)
                {
                    // Only centres within planarReach of the part of the shadow in the strip
                    // |y' - y| <= planarReach can be that near: that part's x extent, widened by
                    // the reach and a cell either side (rounding), bounds the row's cells.
                    const double cy = origin_.y() + h * (y + 0.5);
                    double xl, xr;
                    if (!shadowExtentInStrip(a, b, c, cy - planarReach, cy + planarReach, xl, xr))
                        continue;
                    const double u0 = (xl - planarReach - origin_.x()) * inverseCellSize_ - 0.5;
                    const double u1 = (xr + planarReach - origin_.x()) * inverseCellSize_ - 0.5;
                    if (u0 > double(x1) + 1.0 || u1 < double(x0) - 1.0)
                        continue;
                    first = std::max(x0, int(std::floor(std::max(u0, double(x0) - 1.0))) - 1);
                    last = std::min(x1, int(std::ceil(std::min(u1, double(x1) + 1.0))) + 1);
                }
                for (int x = first; x <= last; ++x)
                {
                    const std::size_t i = cellIndex(x, y, z);
                    if (occupiedCell[i])
                        continue;  // already marked, with the first triangle that did
                    const Vec3 centre = origin_ + h * Vec3(x + 0.5, y + 0.5, z + 0.5);
                    if (planar ? squaredShadowDistance(centre, a, b, c, inverseCellSize_) <= planarReachCells
                               : std::abs(normal.dot(centre - a)) <= reach)
                    {
                        occupiedCell[i] = 1;
                        ++occupied_;  // each cell once: occupied cells are skipped above
                        if (settings.keepTriangles)
                            firstMarks.emplace_back(std::uint32_t(i), std::uint32_t(t));
                    }
                }
            }
    }
    if (settings.keepTriangles)
    {
        // 64 cells per word: the word's mask and the occupied cells before it; then each cell's
        // first triangle at its rank among the occupied cells (index order).
        occupiedMask_.assign((cellCount + 63) / 64, 0);
        occupiedBefore_.assign(occupiedMask_.size(), 0);
        std::uint32_t count = 0;
        for (std::size_t w = 0; w < occupiedMask_.size(); ++w)
        {
            const std::size_t base = w * 64, cells = std::min<std::size_t>(64, cellCount - base);
            std::uint64_t mask = 0;
            for (std::size_t k = 0; k < cells; ++k)
                mask |= std::uint64_t(occupiedCell[base + k] != 0) << k;
            occupiedMask_[w] = mask;
            occupiedBefore_[w] = count;
            count += std::uint32_t(__builtin_popcountll(mask));
        }
        occupiedTriangle_.assign(occupied_, 0);
        for (const auto &[cell, triangle] : firstMarks)
        {
            const std::uint64_t below = occupiedMask_[cell / 64] & ((std::uint64_t(1) << (cell % 64)) - 1);
            occupiedTriangle_[occupiedBefore_[cell / 64] + std::size_t(__builtin_popcountll(below))] = triangle;
        }
    }
    // Half cells of clearance per squared distance (an integer): from 65^2 cells on the codes
    // saturate, so the transform stops there and a table of the smaller ones spares a square root
    // per cell.
    constexpr std::uint16_t kTabled = 65 * 65;
    const std::vector<std::uint16_t> squared = squaredDistanceTransform(occupiedCell, nx_, ny_, nz_, kTabled);

    // Codes: 0 occupied, 1 + half cells outside every solid (at most 126), 128 + half cells inside
    // one (at most 127); every free cell is coded outside first.
    std::vector<std::uint8_t> halfCells(kTabled);
    for (std::size_t k = 0; k < kTabled; ++k)
        halfCells[k] = std::uint8_t(unitsBelow(double(k), 0.0, 2, 127));
    const auto unitsAt = [&](std::size_t i) { return squared[i] < kTabled ? halfCells[squared[i]] : 127; };
    cellBytes_.resize(cellCount);
    for (std::size_t i = 0; i < cellCount; ++i)
        cellBytes_[i] = occupiedCell[i] ? 0 : std::uint8_t(1 + std::min(unitsAt(i), 126));

    // Sides: one exact point-in-solid test per face-connected region of free cells.
    labelled_ = solids != nullptr && !planar;
    if (labelled_ && solids->closedComponentCount() > 0)
    {
        // Each region's first cell (its root run's first, bvh/grid_regions.h) gets the
        // point-in-solid test; every run of the region takes its answer.
        const FreeRuns runs = freeRegionRuns(occupiedCell, nx_, ny_, nz_);
        std::vector<std::uint8_t> runInside(runs.first.size(), 0);
        insideMask_.assign((cellCount + 63) / 64, 0);
        for (std::size_t r = 0; r < runs.first.size(); ++r)
        {
            if (runs.root[r] != r)
                runInside[r] = runInside[runs.root[r]];  // the root comes first
            else
            {
                const std::size_t i = runs.first[r];
                const int x = int(i % nx_), y = int((i / nx_) % ny_), z = int(i / (std::size_t(nx_) * ny_));
                runInside[r] = solids->insideAnySolid(origin_ + h * Vec3(x + 0.5, y + 0.5, z + 0.5));
            }
            if (runInside[r])
                for (std::size_t i = runs.first[r]; i < runs.end[r]; ++i)
                {
                    cellBytes_[i] = std::uint8_t(128 + unitsAt(i));
                    insideMask_[i / 64] |= std::uint64_t(1) << (i % 64);
                }
        }
    }
    hasMarkers_ = !markers.empty() && !planar;

    if (hasMarkers_ && markers.size() <= kMarkersKeptAsPoints)
        markerPoints_ = markers;  // at() measures to each of them: exact, and no second transform
    else if (hasMarkers_)
    {
        std::vector<std::uint8_t> markerCell(cellCount, 0);
        for (const Vec3 &m : markers)
        {
            int x0, x1, y0, y1, z0, z1;
            cellRange(m.x() - boxSlack, m.x() + boxSlack, 0, nx_, x0, x1);
            cellRange(m.y() - boxSlack, m.y() + boxSlack, 1, ny_, y0, y1);
            cellRange(m.z() - boxSlack, m.z() + boxSlack, 2, nz_, z0, z1);
            for (int z = z0; z <= z1; ++z)
                for (int y = y0; y <= y1; ++y)
                    for (int x = x0; x <= x1; ++x)
                        markerCell[cellIndex(x, y, z)] = 1;
        }
        // Whole cells saturate at 255, i.e. from sqrt(squared) = 255 + sqrt(3) on; and
        // from markerReach plus four cells on, whose bound (a capped square gives a smaller one:
        // the units grow with it) is still a cell beyond the reach.
        std::uint32_t markerCap = 65912;
        const double reachCells = std::max(0.0, settings.markerReach) * inverseCellSize_ + 4.0;
        if (reachCells < 257.0)
            markerCap = std::min(markerCap, std::uint32_t(std::ceil(reachCells * reachCells)));
        const std::vector<std::uint32_t> markerSquared = squaredDistanceTransform(markerCell, nx_, ny_, nz_, markerCap);
        markerBytes_.resize(cellCount);
        for (std::size_t i = 0; i < cellCount; ++i)
            markerBytes_[i] = std::uint8_t(unitsBelow(markerSquared[i], 0.5 * kSqrt3, 1, 255));
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
