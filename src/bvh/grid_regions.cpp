// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bvh/grid_regions.h"

#include <algorithm>
#include <cstddef>

namespace hcd
{
FreeRuns freeRegionRuns(const std::vector<std::uint8_t> &occupied, int nx, int ny, int nz)
{
    const std::size_t plane = std::size_t(nx) * ny, rows = std::size_t(ny) * nz;
    // Runs of free cells along x, row by row: union-find over runs rather than cells (a row of a
    // free room is one run).
    FreeRuns runs;
    std::vector<std::uint32_t> &runFirst = runs.first, &runEnd = runs.end, &parent = runs.root;
    std::vector<std::uint32_t> rowRuns(rows + 1, 0);
    for (std::size_t row = 0; row < rows; ++row)
    {
        rowRuns[row] = std::uint32_t(runFirst.size());
        const std::uint8_t *o = occupied.data() + row * std::size_t(nx);
        for (int x = 0; x < nx;)
        {
            if (o[x])
            {
                ++x;
                continue;
            }
            const int first = x;
            while (x < nx && !o[x])
                ++x;
            runFirst.push_back(std::uint32_t(row * std::size_t(nx) + std::size_t(first)));
            runEnd.push_back(std::uint32_t(row * std::size_t(nx) + std::size_t(x)));
        }
    }
    rowRuns[rows] = std::uint32_t(runFirst.size());
    parent.resize(runFirst.size());
    for (std::uint32_t r = 0; r < parent.size(); ++r)
        parent[r] = r;
    // Every parent precedes its child (parent[r] <= r): a root found is the region's first run.
    const auto find = [&](std::uint32_t r) {
        while (parent[r] != r)
        {
            parent[r] = parent[parent[r]];  // path halving
            r = parent[r];
        }
        return r;
    };
    const auto unite = [&](std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a < b)
            parent[b] = a;
        else if (b < a)
            parent[a] = b;
    };
    // Runs of two rows that are face neighbours (one apart in y, or in z) meet where their x
    // ranges overlap; both lists are sorted along x, so one merge finds every overlap.
    const auto uniteOverlaps = [&](std::size_t row, std::size_t neighbourRow, std::uint32_t offset) {
        std::uint32_t a = rowRuns[row], b = rowRuns[neighbourRow];
        const std::uint32_t aEnd = rowRuns[row + 1], bEnd = rowRuns[neighbourRow + 1];
        while (a < aEnd && b < bEnd)
        {
            const std::uint32_t aFirst = runFirst[a] - offset, aLast = runEnd[a] - offset;  // in b's row
            if (aFirst < runEnd[b] && runFirst[b] < aLast)
                unite(b, a);
            if (aLast <= runEnd[b])
                ++a;
            else
                ++b;
        }
    };
    for (std::size_t row = 0; row < rows; ++row)
    {
        const std::size_t y = row % std::size_t(ny);
        if (y > 0)
            uniteOverlaps(row, row - 1, std::uint32_t(nx));
        if (row >= std::size_t(ny))
            uniteOverlaps(row, row - std::size_t(ny), std::uint32_t(plane));
    }
    // In index order every parent is final before its children: one pass flattens every chain.
    for (std::uint32_t r = 0; r < parent.size(); ++r)
        parent[r] = parent[parent[r]];
    return runs;
}

std::vector<std::uint32_t> freeRegions(const std::vector<std::uint8_t> &occupied, int nx, int ny, int nz)
{
    const std::size_t count = std::size_t(nx) * ny * nz;
    const FreeRuns runs = freeRegionRuns(occupied, nx, ny, nz);
    std::vector<std::uint32_t> region(count);
    for (std::size_t i = 0; i < count; ++i)
        region[i] = std::uint32_t(i);  // occupied cells keep their own index
    for (std::size_t r = 0; r < runs.first.size(); ++r)
        std::fill(region.begin() + runs.first[r], region.begin() + runs.end[r], runs.first[runs.root[r]]);
    return region;
}

std::vector<std::uint32_t> freeRegionsByFloodFill(const std::vector<std::uint8_t> &occupied, int nx, int ny, int nz)
{
    const std::size_t count = std::size_t(nx) * ny * nz;
    std::vector<std::uint32_t> region(count);
    for (std::size_t i = 0; i < count; ++i)
        region[i] = std::uint32_t(i);
    std::vector<std::uint8_t> seen(count, 0);
    std::vector<std::size_t> stack;
    for (std::size_t seed = 0; seed < count; ++seed)
    {
        if (occupied[seed] || seen[seed])
            continue;
        stack.assign(1, seed);
        seen[seed] = 1;
        while (!stack.empty())
        {
            const std::size_t i = stack.back();
            stack.pop_back();
            region[i] = std::uint32_t(seed);
            const int x = int(i % std::size_t(nx)), y = int((i / std::size_t(nx)) % std::size_t(ny)),
                      z = int(i / (std::size_t(nx) * ny));
            const int neighbours[6][3] = {{x - 1, y, z}, {x + 1, y, z}, {x, y - 1, z},
                                          {x, y + 1, z}, {x, y, z - 1}, {x, y, z + 1}};
            for (const auto &n : neighbours)
            {
                if (n[0] < 0 || n[1] < 0 || n[2] < 0 || n[0] >= nx || n[1] >= ny || n[2] >= nz)
                    continue;
                const std::size_t j = (std::size_t(n[2]) * ny + n[1]) * nx + n[0];
                if (!occupied[j] && !seen[j])
                {
                    seen[j] = 1;
                    stack.push_back(j);
                }
            }
        }
    }
    return region;
}
}  // namespace hcd
