// SPDX-License-Identifier: BSD-3-Clause
// Face-connected regions of the free cells of a grid: the clearance grid labels each region inside
// or outside the solids with one point-in-solid test (bvh/clearance_grid.h).
#pragma once

#include <cstdint>
#include <vector>

namespace hcd
{
/// `occupied` holds nx * ny * nz flags, x fastest (index (z * ny + y) * nx + x), at most 2^32
/// cells. Returns, for each free cell (occupied[i] == 0), the smallest index of its face-connected
/// region of free cells; occupied cells keep their own index. Union-find over the runs of free
/// cells along x (a row of an empty room is one run), each run joined to the runs it overlaps in
/// the rows before it in y and in z.
std::vector<std::uint32_t> freeRegions(const std::vector<std::uint8_t> &occupied, int nx, int ny, int nz);

/// The same by flood fill from each region's first cell. The reference for the above in tests.
std::vector<std::uint32_t> freeRegionsByFloodFill(const std::vector<std::uint8_t> &occupied, int nx, int ny, int nz);
}  // namespace hcd
