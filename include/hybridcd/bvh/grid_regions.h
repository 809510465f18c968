// SPDX-License-Identifier: BSD-3-Clause
// Face-connected regions of the free cells of a grid: the clearance grid labels each region inside
// or outside the solids with one point-in-solid test (bvh/clearance_grid.h).
#pragma once

#include <cstdint>
#include <vector>

namespace hcd
{
/// The runs of free cells along x of a grid and their face-connected regions: run r covers the
/// cells [first[r], end[r]) of one row, in index order, and root[r] is the region's first run
/// (root[r] <= r; its first cell is the region's smallest index).
struct FreeRuns
{
    std::vector<std::uint32_t> first, end, root;
};

/// `occupied` as below. Union-find over the runs, each joined to the runs it overlaps in the rows
/// before it in y and in z.
FreeRuns freeRegionRuns(const std::vector<std::uint8_t> &occupied, int nx, int ny, int nz);

/// `occupied` holds nx * ny * nz flags, x fastest (index (z * ny + y) * nx + x), fewer than 2^32
/// cells. Returns, for each free cell (occupied[i] == 0), the smallest index of its face-connected
/// region of free cells; occupied cells keep their own index. freeRegionRuns, cell by cell.
std::vector<std::uint32_t> freeRegions(const std::vector<std::uint8_t> &occupied, int nx, int ny, int nz);

/// The same by flood fill from each region's first cell. The reference for the above in tests.
std::vector<std::uint32_t> freeRegionsByFloodFill(const std::vector<std::uint8_t> &occupied, int nx, int ny, int nz);
}  // namespace hcd
