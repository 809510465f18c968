// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bvh/distance_transform.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>

namespace hcd
{
namespace
{
/// Along each row of x: the squared distance to the nearest seed of the row, by one scan from each
/// end (kNoSeedSquaredDistance in a row without seeds).
void nearestSeedAlongX(const std::vector<std::uint8_t> &seeds, int nx, std::size_t rows, std::vector<double> &out)
{
    for (std::size_t row = 0; row < rows; ++row)
    {
        const std::uint8_t *s = seeds.data() + row * std::size_t(nx);
        double *d = out.data() + row * std::size_t(nx);
        int last = -1;  // the latest seed at or before q
        for (int q = 0; q < nx; ++q)
        {
            if (s[q])
                last = q;
            d[q] = last < 0 ? kNoSeedSquaredDistance : double(q - last) * double(q - last);
        }
        int next = -1;  // the earliest seed at or after q
        for (int q = nx - 1; q >= 0; --q)
        {
            if (s[q])
                next = q;
            if (next >= 0)
                d[q] = std::min(d[q], double(next - q) * double(next - q));
        }
    }
}

/// Felzenszwalb and Huttenlocher's exact 1D squared distance transform (lower envelope of
/// parabolas) of f[0, n), with only the entries below kNoSeedSquaredDistance as parabolas (the
/// others can never be lowest). On integer inputs the envelope breakpoints are rationals with
/// denominators below 2n, so double rounding never changes which parabola is lowest at an integer.
void lowerEnvelope(const double *f, int n, double *d, int *v, double *z)
{
    int k = -1;
    for (int q = 0; q < n; ++q)
    {
        if (!(f[q] < kNoSeedSquaredDistance))
            continue;
        if (k < 0)
        {
            k = 0;
            v[0] = q;
            z[0] = -std::numeric_limits<double>::infinity();
            z[1] = std::numeric_limits<double>::infinity();
            continue;
        }
        const double lifted = f[q] + double(q) * q;
        double s = (lifted - (f[v[k]] + double(v[k]) * v[k])) / (2.0 * q - 2.0 * v[k]);
        while (s <= z[k])  // z[0] is -infinity: k stays at least 0
        {
            --k;
            s = (lifted - (f[v[k]] + double(v[k]) * v[k])) / (2.0 * q - 2.0 * v[k]);
        }
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = std::numeric_limits<double>::infinity();
    }
    if (k < 0)
    {
        std::fill(d, d + n, kNoSeedSquaredDistance);
        return;
    }
    k = 0;
    for (int q = 0; q < n; ++q)
    {
        while (z[k + 1] < q)
            ++k;
        d[q] = double(q - v[k]) * (q - v[k]) + f[v[k]];
    }
}
}  // namespace

std::vector<double> squaredDistanceTransform(const std::vector<std::uint8_t> &seeds, int nx, int ny, int nz)
{
    const std::size_t plane = std::size_t(nx) * ny, count = plane * nz;
    std::vector<double> grid(count);
    if (count == 0)
        return grid;
    nearestSeedAlongX(seeds, nx, std::size_t(ny) * nz, grid);
    const int longest = std::max({nx, ny, nz});
    std::vector<double> f(longest), d(longest), z(longest + 1);
    std::vector<int> v(longest);
    // One column along y or z at a time; consecutive columns are neighbours in x, so that the cache
    // lines one column reads serve the next seven.
    const auto column = [&](std::size_t first, std::size_t stride, int n) {
        bool reached = false;
        for (int q = 0; q < n; ++q)
        {
            f[q] = grid[first + std::size_t(q) * stride];
            reached = reached || f[q] < kNoSeedSquaredDistance;
        }
        if (!reached)
            return;  // nothing along this column: it stays unreached
        lowerEnvelope(f.data(), n, d.data(), v.data(), z.data());
        for (int q = 0; q < n; ++q)
            grid[first + std::size_t(q) * stride] = d[q];
    };
    if (ny > 1)
        for (int zi = 0; zi < nz; ++zi)
            for (int x = 0; x < nx; ++x)
                column(std::size_t(zi) * plane + std::size_t(x), std::size_t(nx), ny);
    if (nz > 1)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x)
                column(std::size_t(y) * nx + std::size_t(x), plane, nz);
    return grid;
}

std::vector<double> squaredDistanceTransformBruteForce(const std::vector<std::uint8_t> &seeds, int nx, int ny, int nz)
{
    const std::size_t count = std::size_t(nx) * ny * nz;
    std::vector<double> grid(count, kNoSeedSquaredDistance);
    std::vector<std::size_t> seedCells;
    for (std::size_t i = 0; i < count; ++i)
        if (seeds[i])
            seedCells.push_back(i);
    const auto coordinates = [&](std::size_t i) {
        return std::array<double, 3>{double(i % std::size_t(nx)), double((i / std::size_t(nx)) % std::size_t(ny)),
                                     double(i / (std::size_t(nx) * ny))};
    };
    for (std::size_t i = 0; i < count; ++i)
    {
        const auto a = coordinates(i);
        for (std::size_t s : seedCells)
        {
            const auto b = coordinates(s);
            const double squared =
                (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
            grid[i] = std::min(grid[i], squared);
        }
    }
    return grid;
}
}  // namespace hcd
