// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bvh/distance_transform.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace hcd
{
namespace
{
/// The smallest distance r (in cells) with r * r >= cap: gaps of r or more saturate.
std::int64_t saturatingGap(std::int64_t cap)
{
    std::int64_t r = std::int64_t(std::sqrt(double(cap)));
    while (r * r < cap)
        ++r;
    while (r > 0 && (r - 1) * (r - 1) >= cap)
        --r;
    return r;
}

/// Along each row of x: the squared distance to the nearest seed of the row, by one scan from each
/// end, or `cap` (also in a row without seeds).
template <class Value>
void nearestSeedAlongX(const std::vector<std::uint8_t> &seeds, int nx, std::size_t rows, Value cap, Value *out)
{
    const std::int64_t reach = saturatingGap(cap);
    for (std::size_t row = 0; row < rows; ++row)
    {
        const std::uint8_t *s = seeds.data() + row * std::size_t(nx);
        Value *d = out + row * std::size_t(nx);
        std::int64_t last = -reach;  // the latest seed at or before q, or one out of reach
        for (int q = 0; q < nx; ++q)
        {
            if (s[q])
                last = q;
            const std::int64_t gap = q - last;
            d[q] = gap < reach ? Value(gap * gap) : cap;
        }
        std::int64_t next = std::int64_t(nx) - 1 + reach;  // the earliest seed at or after q
        for (int q = nx - 1; q >= 0; --q)
        {
            if (s[q])
                next = q;
            const std::int64_t gap = next - q;
            if (gap < reach)
                d[q] = std::min(d[q], Value(gap * gap));
        }
    }
}

/// Felzenszwalb and Huttenlocher's exact 1D squared distance transform (lower envelope of
/// parabolas) of f[0, n), in place, capped at `cap`, with only the entries below the cap as
/// parabolas (the others can never bring a value below it). The breakpoint of the parabolas at v
/// and q is (q + v) / 2 + (f[q] - f[v]) / (2 (q - v)): a rational with a denominator below 2n,
/// whose double never lands on the wrong side of an integer. Scratch: v, h (n each) and z (n + 1).
void lowerEnvelope(std::int64_t *f, int n, std::int64_t cap, int *v, std::int64_t *h, double *z)
{
    int k = -1;
    for (int q = 0; q < n; ++q)
    {
        if (f[q] >= cap)
            continue;
        if (k < 0)
        {
            k = 0;
            v[0] = q;
            h[0] = f[q];
            z[0] = -std::numeric_limits<double>::infinity();
            z[1] = std::numeric_limits<double>::infinity();
            continue;
        }
        const auto breakpoint = [&](int at) {
            return 0.5 * double(q + at) + double(f[q] - f[at]) / (2.0 * double(q - at));
        };
        double s = breakpoint(v[k]);
        while (s <= z[k])  // z[0] is -infinity: k stays at least 0
        {
            --k;
            s = breakpoint(v[k]);
        }
        ++k;
        v[k] = q;
        h[k] = f[q];
        z[k] = s;
        z[k + 1] = std::numeric_limits<double>::infinity();
    }
    if (k < 0)
        return;  // every entry is already at the cap
    const int last = k;
    k = 0;
    for (int q = 0; q < n; ++q)
    {
        while (k < last && z[k + 1] < q)
            ++k;
        const std::int64_t gap = q - v[k];  // |gap| < n < 2^31 and h[k] < cap <= 2^32: no overflow
        f[q] = std::min(cap, gap * gap + h[k]);
    }
}
}  // namespace

template <class Value>
std::vector<Value> squaredDistanceTransform(const std::vector<std::uint8_t> &seeds, int nx, int ny, int nz, Value cap)
{
    const std::size_t plane = std::size_t(nx) * ny, count = plane * nz;
    std::vector<Value> grid(count);
    if (count == 0)
        return grid;
    nearestSeedAlongX(seeds, nx, std::size_t(ny) * nz, cap, grid.data());
    const int longest = std::max({nx, ny, nz});
    std::vector<std::int64_t> f(longest), h(longest);
    std::vector<double> z(longest + 1);
    std::vector<int> v(longest);
    // One column along y or z at a time; consecutive columns are neighbours in x, so that the cache
    // lines one column reads serve the next ones.
    const auto column = [&](std::size_t first, std::size_t stride, int n) {
        bool reached = false;
        for (int q = 0; q < n; ++q)
        {
            f[q] = grid[first + std::size_t(q) * stride];
            reached = reached || f[q] < cap;
        }
        if (!reached)
            return;  // nothing along this column: it stays at the cap
        lowerEnvelope(f.data(), n, cap, v.data(), h.data(), z.data());
        for (int q = 0; q < n; ++q)
            grid[first + std::size_t(q) * stride] = Value(f[q]);
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

template std::vector<std::uint16_t> squaredDistanceTransform(const std::vector<std::uint8_t> &, int, int, int,
                                                             std::uint16_t);
template std::vector<std::uint32_t> squaredDistanceTransform(const std::vector<std::uint8_t> &, int, int, int,
                                                             std::uint32_t);

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
