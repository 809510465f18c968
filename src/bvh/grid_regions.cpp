// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bvh/grid_regions.h"

#include <cstddef>

namespace hcd
{
std::vector<std::uint32_t> freeRegions(const std::vector<std::uint8_t> &occupied, int nx, int ny, int nz)
{
    const std::size_t plane = std::size_t(nx) * ny;
    std::vector<std::uint32_t> parent(plane * nz);
    // Every parent precedes its child (parent[i] <= i): a root found is the region's smallest index.
    const auto find = [&](std::uint32_t i) {
        while (parent[i] != i)
        {
            parent[i] = parent[parent[i]];  // path halving
            i = parent[i];
        }
        return i;
    };
    const auto unite = [&](std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a < b)
            parent[b] = a;
        else if (b < a)
            parent[a] = b;
    };
    std::uint32_t i = 0;
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x, ++i)
            {
                parent[i] = i;
                if (occupied[i])
                    continue;
                if (x > 0 && !occupied[i - 1])
                    parent[i] = parent[i - 1];  // parent[i - 1] < i keeps parent[i] <= i
                if (y > 0 && !occupied[i - nx])
                    unite(i - std::uint32_t(nx), i);
                if (z > 0 && !occupied[i - plane])
                    unite(i - std::uint32_t(plane), i);
            }
    // In index order every parent is final before its children: one pass flattens every chain.
    for (std::uint32_t j = 0; j < parent.size(); ++j)
        parent[j] = parent[parent[j]];
    return parent;
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
