// SPDX-License-Identifier: BSD-3-Clause
// The clearance grid's distance transform against brute force (every cell against every seed),
// bit for bit and capped at several heights, on random grids of every shape: flat, one cell thick,
// long and thin, without seeds, with one seed and with seeds almost everywhere.
#include "support/test_support.h"

#include "hybridcd/bvh/distance_transform.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

using namespace hcd;

namespace
{
/// The capped transform in `Value` against min(brute force, cap), cell by cell.
template <class Value>
void expectCappedBruteForce(const std::vector<std::uint8_t> &seeds, int nx, int ny, int nz,
                            const std::vector<double> &reference, Value cap)
{
    const std::vector<Value> fast = squaredDistanceTransform(seeds, nx, ny, nz, cap);
    ASSERT_EQ(fast.size(), reference.size());
    for (std::size_t i = 0; i < fast.size(); ++i)
        ASSERT_EQ(double(fast[i]), std::min(reference[i], double(cap)))
            << "cell " << i << " of " << nx << "x" << ny << "x" << nz << ", cap " << cap;
}

/// Uncapped in 32 bits, and capped where the cap cuts some rows short and where it cuts almost all.
void expectSameAsBruteForce(const std::vector<std::uint8_t> &seeds, int nx, int ny, int nz)
{
    const std::vector<double> reference = squaredDistanceTransformBruteForce(seeds, nx, ny, nz);
    expectCappedBruteForce<std::uint32_t>(seeds, nx, ny, nz, reference, std::numeric_limits<std::uint32_t>::max());
    expectCappedBruteForce<std::uint16_t>(seeds, nx, ny, nz, reference, std::numeric_limits<std::uint16_t>::max());
    for (std::uint16_t cap : {std::uint16_t(1), std::uint16_t(2), std::uint16_t(17), std::uint16_t(50)})
        expectCappedBruteForce<std::uint16_t>(seeds, nx, ny, nz, reference, cap);
}
}  // namespace

TEST(DistanceTransform, SameAsBruteForceOnRandomGrids)
{
    test::TestRandom rng(test::seeded(29));
    std::uniform_int_distribution<int> side(1, 14);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < test::cases(400); ++trial)
    {
        const int nx = side(rng), ny = side(rng), nz = side(rng);
        const std::size_t count = std::size_t(nx) * ny * nz;
        // From no seed at all to nearly every cell a seed.
        const double density = trial % 5 == 0 ? 0.0 : std::pow(u(rng), 3.0);
        std::vector<std::uint8_t> seeds(count);
        for (auto &s : seeds)
            s = u(rng) < density;
        expectSameAsBruteForce(seeds, nx, ny, nz);
    }
}

TEST(DistanceTransform, OneSeedInLongFlatAndThinGrids)
{
    test::TestRandom rng(test::seeded(31));
    for (const auto &shape : std::vector<std::array<int, 3>>{
             {1, 1, 1}, {200, 1, 1}, {1, 200, 1}, {1, 1, 200}, {60, 50, 1}, {1, 40, 45}, {37, 1, 41}, {23, 29, 31}})
    {
        const std::size_t count = std::size_t(shape[0]) * shape[1] * shape[2];
        std::vector<std::uint8_t> seeds(count, 0);
        seeds[std::uniform_int_distribution<std::size_t>(0, count - 1)(rng)] = 1;
        expectSameAsBruteForce(seeds, shape[0], shape[1], shape[2]);
        seeds.assign(count, 0);
        seeds[0] = seeds[count - 1] = 1;  // opposite corners
        expectSameAsBruteForce(seeds, shape[0], shape[1], shape[2]);
    }
}

TEST(DistanceTransform, NoSeedLeavesEveryCellAtTheCap)
{
    const std::vector<std::uint32_t> d =
        squaredDistanceTransform(std::vector<std::uint8_t>(6 * 5 * 4, 0), 6, 5, 4, std::uint32_t(1000));
    for (std::uint32_t v : d)
        EXPECT_EQ(v, 1000u);
}
