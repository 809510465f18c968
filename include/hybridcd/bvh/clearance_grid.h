// SPDX-License-Identifier: BSD-3-Clause
// A uniform grid over the environment that bounds, per cell, how far the surface is (from below),
// and says on which side of every closed solid the cell lies: a cheap first layer that proves most
// free poses free without touching a hierarchy (the seed's occupancy grids, §3.1, made exact).
#pragma once

#include "hybridcd/geometry/solid_components.h"
#include "hybridcd/geometry/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace hcd
{
struct ClearanceGridSettings
{
    /// Upper bound on the number of cells (one byte each, twice with more than eight markers; at
    /// most 2^31).
    std::size_t maxCells = std::size_t(1) << 19;
    /// The grid covers the mesh's bounding box grown by this much on every side (world units).
    double margin = 0.0;
    /// Marker distances are needed only up to about this far (world units): from a few cells
    /// beyond it, markerClearance saturates at a bound still above it (a lower bound all the
    /// same), and the markers' distance transform stops there.
    double markerReach = std::numeric_limits<double>::infinity();
    /// Keep, for each occupied cell, one triangle that marked it (triangleNear()).
    bool keepTriangles = false;
    /// A footprint grid: the triangles count by their shadows on the plane z = 0 (each point's
    /// (x, y, 0)), the cells are one layer of squares centred on that plane, and queries come at
    /// z = 0, where the clearance bounds the distance in x and y to every shadow. No sides or
    /// markers. For motions in the plane, with the environment's triangles at the robot's height.
    bool planar = false;
};

/// What the grid knows about one point (world frame).
struct ClearanceSample
{
    /// Lower bound on the distance from the point to any triangle of the mesh (0 when unknown).
    double clearance = 0.0;
    /// The point is outside every closed component (proved); false when unknown.
    bool outside = false;
    /// The point is inside some closed component (proved), at least `clearance` from its surface:
    /// it lies in a free cell, and no triangle comes within the rounding slack of a free cell, far
    /// more than the rounding in the point or its cell index.
    bool inside = false;
    /// Lower bound on the distance from the point to the nearest marker point.
    double markerClearance = 0.0;
};

/// Cells are closed cubes of side `cellSize()`. A cell is occupied when a triangle may touch it
/// (bounding box and plane tests with an outward margin, so never missed). For a free cell, the
/// squared distance in cells to the nearest occupied cell centre (exact Euclidean distance
/// transform on integers) gives the bound (d - sqrt(3)/2) * cellSize on the distance from the
/// cell's centre to the surface, kept in half cells; a point p of the cell subtracts its own
/// distance from the centre (at most sqrt(3)/2 cells). Face-adjacent free cells are on the same
/// side of every surface, so one exact point-in-solid test per connected free region labels all
/// its cells. Marker points (e.g. one vertex per component) get a distance bound: measured to each
/// of them when there are at most eight, else from a second channel of cells, in whole cells from
/// any point of the cell. Immutable after construction; safe to query from many threads.
class ClearanceGrid
{
public:
    ClearanceGrid() = default;
    /// `solids`, when given, is the point-in-solid query of `mesh` (labels inside/outside);
    /// without it no cell is labelled and `outside`/`inside` stay false.
    ClearanceGrid(const TriangleMesh &mesh, const SolidQuery *solids, const std::vector<Vec3> &markers,
                  ClearanceGridSettings settings = {});

    bool empty() const { return cellBytes_.empty(); }
    /// Inline (below): every grid-first check starts here.
    ClearanceSample at(const Vec3 &p) const;

    /// `at(p).clearance > reach` (and `at(p).outside` when `outside` is asked for), decided without
    /// square roots inside the grid: the free-pose proofs' test, once per cover sphere. Inline
    /// (below).
    bool clears(const Vec3 &p, double reach, bool outside) const;

    /// `at(p).inside` with at(p).clearance above `rounding` (world units, the error in p) unless
    /// the rounding is below half of certainMargin(): p is then certainly inside a solid. Reads a
    /// bit per cell, not the codes (an eighth of their memory), so that the point-in-solid proof's
    /// lookups, mostly of cells outside every solid, stay in cache. Inline (below).
    bool certainlyInside(const Vec3 &p, double rounding) const;

    /// A triangle of the mesh that marked the cell holding p, or -1 when that cell is free, lies
    /// beyond the grid, or triangles were not kept. Near p: within the cell's diagonal of it.
    std::int64_t triangleNear(const Vec3 &p) const;

    /// How far beyond every free cell the surface is known not to come (world units): points within
    /// it of a free cell are on the cell's side of every solid.
    double certainMargin() const { return roundingSlack_; }

    double cellSize() const { return cellSize_; }
    std::array<int, 3> cells() const { return {nx_, ny_, nz_}; }
    std::size_t occupiedCells() const { return occupied_; }
    std::size_t memoryBytes() const
    {
        return cellBytes_.size() + markerBytes_.size() + sizeof(Vec3) * markerPoints_.size() +
               12 * occupiedMask_.size() + 4 * occupiedTriangle_.size() + 8 * insideMask_.size();
    }
    double buildSeconds() const { return buildSeconds_; }

private:
    /// The cell holding a point, or `inGrid` false beyond the grid (and for a non-finite point):
    /// the cell's index and the point's coordinates in cells from the grid's origin.
    struct CellPoint
    {
        bool inGrid = false;
        std::size_t index = 0;
        Vec3 coordinates = Vec3::Zero();
        std::size_t ix = 0, iy = 0, iz = 0;  ///< the cell's place along x, y and z
        /// The point's offset from its cell's centre, in cells (computed only where a proof needs it).
        Vec3 offCentre() const { return coordinates - Vec3(double(ix) + 0.5, double(iy) + 0.5, double(iz) + 0.5); }
    };
    CellPoint locate(const Vec3 &p) const;
    /// Per axis, how far p lies beyond the mesh's bounding box (zero within it), in world units.
    Vec3 gapToMeshBox(const Vec3 &p) const { return boxSeparation(p, p, meshMin_, meshMax_); }
    /// Slack for rounding in p's cell and in the distances read for it, in world units.
    double slackAt(const Vec3 &p) const { return roundingSlack_ + 1e-9 * p.cwiseAbs().maxCoeff(); }

    Vec3 origin_ = Vec3::Zero();
    Vec3 meshMin_ = Vec3::Zero(), meshMax_ = Vec3::Zero();
    double cellSize_ = 0.0, inverseCellSize_ = 0.0;
    /// Slack for rounding in the cell index of a query point (world units).
    double roundingSlack_ = 0.0;
    int nx_ = 0, ny_ = 0, nz_ = 0;
    bool labelled_ = false;
    bool hasMarkers_ = false;
    /// Per cell, the surface code, 0: occupied; 1..127: outside every solid, the cell's centre at
    /// least (code - 1) half cells from the surface; 128..255: inside a solid, (code - 128) half
    /// cells. One byte per cell, so that the codes every proof reads stay in cache.
    std::vector<std::uint8_t> cellBytes_;
    /// Bit i % 64 of insideMask_[i / 64]: cell i is inside a solid (its code is 128 or more).
    /// Empty when cells are not labelled (no solids, a planar grid, or no closed component).
    std::vector<std::uint64_t> insideMask_;
    /// With at most kMarkersKeptAsPoints markers, the markers themselves: at() measures to each.
    static constexpr std::size_t kMarkersKeptAsPoints = 8;
    std::vector<Vec3> markerPoints_;
    /// With more markers, per cell, a lower bound on the distance to the nearest marker in whole
    /// cells (the byte's value, saturating at 255, or from a few cells beyond markerReach on); read far
    /// less often, so kept apart.
    std::vector<std::uint8_t> markerBytes_;
    /// Lower bound on the distance from p to the nearest marker (markers kept as points), less
    /// `slack`.
    double markerPointClearance(const Vec3 &p, double slack) const;
    /// Kept triangles: bit i % 64 of occupiedMask_[i / 64] marks occupied cell i; occupiedBefore_
    /// counts occupied cells of earlier words, so a cell's rank indexes occupiedTriangle_.
    std::vector<std::uint64_t> occupiedMask_;
    std::vector<std::uint32_t> occupiedBefore_;
    std::vector<std::uint32_t> occupiedTriangle_;
    std::size_t occupied_ = 0;
    double buildSeconds_ = 0.0;
};

inline ClearanceGrid::CellPoint ClearanceGrid::locate(const Vec3 &p) const
{
    const Vec3 f = (p - origin_) * inverseCellSize_;
    CellPoint c;
    if (!(f.x() >= 0.0 && f.y() >= 0.0 && f.z() >= 0.0 && f.x() < nx_ && f.y() < ny_ && f.z() < nz_))
        return c;
    c.ix = std::size_t(f.x());
    c.iy = std::size_t(f.y());
    c.iz = std::size_t(f.z());
    c.inGrid = true;
    c.index = (c.iz * std::size_t(ny_) + c.iy) * std::size_t(nx_) + c.ix;
    c.coordinates = f;
    return c;
}

inline ClearanceSample ClearanceGrid::at(const Vec3 &p) const
{
    ClearanceSample s;
    if (cellBytes_.empty())
    {
        s.clearance = s.markerClearance = std::numeric_limits<double>::infinity();
        s.outside = true;
        return s;
    }
    const double slack = slackAt(p);
    const CellPoint cell = locate(p);
    if (!cell.inGrid)
    {
        // Beyond the grid: the mesh's bounding box bounds everything, solids and markers included.
        const double d = gapToMeshBox(p).norm() * (1.0 - 1e-12) - slack;  // NaN stays "unknown"
        s.clearance = d > 0.0 ? d : 0.0;
        s.outside = d > 0.0;
        s.markerClearance = !hasMarkers_             ? std::numeric_limits<double>::infinity()
                            : !markerPoints_.empty() ? markerPointClearance(p, slack)
                                                     : s.clearance;
        return s;
    }
    const std::uint8_t code = cellBytes_[cell.index];
    if (code != 0)
    {
        const bool inside = code >= 128;
        // Less p's own distance from its cell's centre (its rounding is within `slack`).
        s.clearance =
            std::max(0.0, ((inside ? code - 128 : code - 1) * 0.5 - cell.offCentre().norm()) * cellSize_ - slack);
        s.inside = labelled_ && inside;
        s.outside = labelled_ && !inside;
    }
    s.markerClearance = !hasMarkers_             ? std::numeric_limits<double>::infinity()
                        : !markerPoints_.empty() ? markerPointClearance(p, slack)
                                                 : std::max(0.0, markerBytes_[cell.index] * cellSize_ - slack);
    return s;
}

inline double ClearanceGrid::markerPointClearance(const Vec3 &p, double slack) const
{
    if (!p.allFinite())
        return 0.0;
    double nearest = std::numeric_limits<double>::infinity();
    for (const Vec3 &m : markerPoints_)
        nearest = std::min(nearest, (m - p).squaredNorm());
    // Rounding in the squares and the root is far below 1e-12 of the distance.
    const double d = std::sqrt(nearest) * (1.0 - 1e-12) - slack;
    return d > 0.0 ? d : 0.0;
}

inline bool ClearanceGrid::certainlyInside(const Vec3 &p, double rounding) const
{
    if (insideMask_.empty())
        return false;
    const CellPoint cell = locate(p);
    if (!cell.inGrid || !((insideMask_[cell.index / 64] >> (cell.index % 64)) & 1u))
        return false;
    return rounding < 0.5 * certainMargin() || at(p).clearance > rounding;
}

inline bool ClearanceGrid::clears(const Vec3 &p, double reach, bool outside) const
{
    if (cellBytes_.empty())
        return true;
    const CellPoint cell = locate(p);
    if (!cell.inGrid)
    {
        // Beyond the grid (or not finite): at()'s box distance, |gap| (1 - 1e-12) - slack > reach
        // (which also puts p outside), squared, with 1e-9 to spare for rounding.
        const double need = (reach + slackAt(p)) * (1.0 + 1e-9);
        return gapToMeshBox(p).squaredNorm() > need * need;
    }
    const std::uint8_t code = cellBytes_[cell.index];
    const bool inside = code >= 128;
    if (code == 0 || (outside && (inside || !labelled_)))
        return false;
    // at(): (units / 2 - offCentre) * cellSize - slack > reach, i.e. offCentre < room (in cells),
    // less 1e-9 of a cell, so that rounding never lets this clear where at() would not.
    const double room = (inside ? code - 128 : code - 1) * 0.5 - (reach + slackAt(p)) * inverseCellSize_ - 1e-9;
    return room > 0.0 && cell.offCentre().squaredNorm() < room * room;
}
}  // namespace hcd
