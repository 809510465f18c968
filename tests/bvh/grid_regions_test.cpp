// SPDX-License-Identifier: BSD-3-Clause
// The clearance grid's free regions (union-find over runs of free cells) against a flood fill from
// each region's first cell, on random grids and on shapes whose regions merge late: a spiral, combs,
// a U open only at the far end, and runs that meet only corner to corner.
#include "support/test_support.h"

#include "hybridcd/bvh/grid_regions.h"

#include <gtest/gtest.h>

#include <random>

using namespace hcd;

namespace
{
void expectSameAsFloodFill(const std::vector<std::uint8_t> &occupied, int nx, int ny, int nz)
{
    const std::vector<std::uint32_t> fast = freeRegions(occupied, nx, ny, nz);
    const std::vector<std::uint32_t> reference = freeRegionsByFloodFill(occupied, nx, ny, nz);
    ASSERT_EQ(fast, reference) << nx << "x" << ny << "x" << nz;
}

std::size_t regionCount(const std::vector<std::uint8_t> &occupied, const std::vector<std::uint32_t> &region)
{
    std::size_t count = 0;
    for (std::size_t i = 0; i < region.size(); ++i)
        count += !occupied[i] && region[i] == i;
    return count;
}
}  // namespace

TEST(GridRegions, SameAsFloodFillOnRandomGrids)
{
    test::TestRandom rng(test::seeded(37));
    std::uniform_int_distribution<int> side(1, 16);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::size_t manyRegions = 0;
    for (int trial = 0; trial < test::cases(400); ++trial)
    {
        const int nx = side(rng), ny = side(rng), nz = side(rng);
        // Around the percolation threshold regions are many and long: late merges everywhere.
        const double density = 0.2 + 0.5 * u(rng);
        std::vector<std::uint8_t> occupied(std::size_t(nx) * ny * nz);
        for (auto &o : occupied)
            o = u(rng) < density;
        expectSameAsFloodFill(occupied, nx, ny, nz);
        manyRegions += regionCount(occupied, freeRegions(occupied, nx, ny, nz)) > 3;
    }
    EXPECT_GT(manyRegions, std::size_t(test::cases(400) / 4));
}

TEST(GridRegions, SpiralCombsAndLateJoins)
{
    // A square spiral wall in each z layer: one free corridor whose cells meet their region's
    // first cell only at the far end of the winding.
    const int n = 21;
    std::vector<std::uint8_t> spiral(std::size_t(n) * n * 2, 0);
    for (int z = 0; z < 2; ++z)
    {
        int lo = 0, hi = n - 1;
        for (int ring = 0; lo <= hi; ++ring, lo += 2, hi -= 2)
        {
            for (int k = lo; k <= hi; ++k)
            {
                spiral[(std::size_t(z) * n + lo) * n + k] = 1;
                spiral[(std::size_t(z) * n + hi) * n + k] = 1;
                spiral[(std::size_t(z) * n + k) * n + lo] = 1;
                spiral[(std::size_t(z) * n + k) * n + hi] = 1;
            }
            if (lo + 1 <= hi)
                spiral[(std::size_t(z) * n + lo + 1) * n + lo] = 0;  // the ring's door
        }
    }
    expectSameAsFloodFill(spiral, n, n, 2);
    // A comb: teeth along y joined only at the far end of x, in the last z layer.
    const int w = 17, h = 9, d = 3;
    std::vector<std::uint8_t> comb(std::size_t(w) * h * d, 0);
    for (int z = 0; z < d; ++z)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                comb[(std::size_t(z) * h + y) * w + x] = (x % 2 == 1 && y < h - 1) || (z < d - 1 && y == h - 1);
    expectSameAsFloodFill(comb, w, h, d);
    // A U open only at its far end: both arms are one region.
    std::vector<std::uint8_t> u(std::size_t(9) * 9, 0);
    for (int y = 0; y < 8; ++y)
        u[std::size_t(y) * 9 + 4] = 1;
    expectSameAsFloodFill(u, 9, 9, 1);
    EXPECT_EQ(regionCount(u, freeRegions(u, 9, 9, 1)), 1u);
    // Free cells on a diagonal, in y and in z: runs that touch only at corners stay apart.
    std::vector<std::uint8_t> stairs(std::size_t(7) * 7 * 7, 1);
    for (int k = 0; k < 7; ++k)
    {
        stairs[std::size_t(k) * 7 + k] = 0;                  // z = 0: (k, k)
        stairs[(std::size_t(k) * 7 + 3) * 7 + (6 - k)] = 0;  // y = 3: x and z on a diagonal
    }
    expectSameAsFloodFill(stairs, 7, 7, 7);
    EXPECT_EQ(regionCount(stairs, freeRegions(stairs, 7, 7, 7)), 14u);  // every free cell alone
    // Every cell occupied, and none.
    expectSameAsFloodFill(std::vector<std::uint8_t>(60, 1), 3, 4, 5);
    expectSameAsFloodFill(std::vector<std::uint8_t>(60, 0), 3, 4, 5);
}
