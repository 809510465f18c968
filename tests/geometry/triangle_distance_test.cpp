// SPDX-License-Identifier: BSD-3-Clause
// The fast paths of geometry/triangle_distance.h against triangleDistance itself, which the
// brute-force checker uses: trianglesWithinDistance must give `triangleDistance <= bound` on every
// pair and bound, disjointTriangleDistance the same bits on every pair that does not intersect (and
// disjointTriangleDistanceBelow the same bits as the minimum of its best and that), and
// triangleDistance must bracket a dense sampling of the two triangles.
#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"

#include "support/test_support.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace
{
using hcd::Vec3;
using Triangle = std::array<Vec3, 3>;

// Pairs of random triangles at `scale`: general ones, nearly coplanar ones (the second a copy of the
// first, shifted and tilted by tiny amounts), and ones snapped to a coarse lattice, so that shared
// vertices, touching edges, coplanar overlaps and crossings all occur.
std::vector<std::array<Triangle, 2>> trianglePairs(double scale, std::size_t count, hcd::test::TestRandom &rng)
{
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> lattice(-2, 2);
    std::uniform_int_distribution<int> kind(0, 2);
    const auto point = [&] { return Vec3(unit(rng), unit(rng), unit(rng)); };
    std::vector<std::array<Triangle, 2>> pairs;
    for (std::size_t i = 0; i < count; ++i)
    {
        Triangle a, b;
        switch (kind(rng))
        {
        case 0:
            a = {point(), point(), point()};
            b = {point() + Vec3(0.8, 0, 0), point(), point()};
            break;
        case 1:
        {
            a = {point(), point(), point()};
            const Vec3 shift = 1e-3 * point();
            for (int k = 0; k < 3; ++k)
                b[std::size_t(k)] = a[std::size_t(2 - k)] + shift + 1e-9 * point();
            break;
        }
        default:
            for (Triangle *t : {&a, &b})
                for (Vec3 &v : *t)
                    v = 0.5 * Vec3(lattice(rng), lattice(rng), lattice(rng));
            break;
        }
        for (Triangle *t : {&a, &b})
            for (Vec3 &v : *t)
                v *= scale;
        pairs.push_back({a, b});
    }
    return pairs;
}

double distanceOf(const std::array<Triangle, 2> &p)
{
    return hcd::triangleDistance(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2]);
}

TEST(TriangleDistance, WithinDistanceAgreesWithTheDistanceForEveryBound)
{
    hcd::test::TestRandom rng(hcd::test::seeded(2711));
    std::size_t within = 0, outside = 0;
    for (const double scale : {1e-6, 1e-2, 1.0, 1e3, 1e6})
        for (const auto &p : trianglePairs(scale, 3000, rng))
        {
            const double d = distanceOf(p);
            const double inf = std::numeric_limits<double>::infinity();
            for (const double bound :
                 {0.0, -1.0, d, std::nextafter(d, inf), std::nextafter(d, -inf), d * (1 + 1e-12), d * (1 - 1e-12),
                  0.5 * d, 2.0 * d, 1e-3 * scale, scale, inf, std::numeric_limits<double>::quiet_NaN()})
            {
                const bool expected = d <= bound;
                ASSERT_EQ(hcd::trianglesWithinDistance(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2], bound),
                          expected)
                    << "scale " << scale << ", distance " << d << ", bound " << bound;
                (expected ? within : outside) += 1;
            }
        }
    // Both answers are common, so neither side of the test is idle.
    EXPECT_GT(within, 20000u);
    EXPECT_GT(outside, 20000u);
}

TEST(TriangleDistance, DisjointDistanceIsTheDistanceBitForBit)
{
    hcd::test::TestRandom rng(hcd::test::seeded(2712));
    std::size_t disjoint = 0;
    for (const double scale : {1e-6, 1.0, 1e6})
        for (const auto &p : trianglePairs(scale, 3000, rng))
        {
            if (hcd::trianglesIntersect(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2]))
                continue;
            ++disjoint;
            ASSERT_EQ(hcd::disjointTriangleDistance(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2]),
                      distanceOf(p));
        }
    EXPECT_GT(disjoint, 3000u);
}

// The pruned distance against the full one, for bests around the distance itself, on the pairs above,
// on slivers (a corner within 1e-9 of the opposite edge) and on small triangles far from the origin.
TEST(TriangleDistance, DistanceBelowABestIsTheMinimumBitForBit)
{
    hcd::test::TestRandom rng(hcd::test::seeded(2713));
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<std::array<Triangle, 2>> pairs;
    for (const double scale : {1e-6, 1e-2, 1.0, 1e3, 1e6})
        for (const auto &p : trianglePairs(scale, 1500, rng))
            pairs.push_back(p);
    for (std::size_t i = 0; i < 1500; ++i)
    {
        std::array<Triangle, 2> p = trianglePairs(1.0, 1, rng).front();
        if (i % 2 == 0)
            for (Triangle &t : p)  // a sliver: the third corner almost on the first edge
                t[2] = 0.5 * (t[0] + t[1]) + 1e-9 * Vec3(unit(rng), unit(rng), unit(rng));
        else
            for (Triangle &t : p)  // tiny triangles far out
                for (Vec3 &v : t)
                    v = Vec3(3e6, -2e6, 1e6) + 1e-3 * v;
        pairs.push_back(p);
    }
    std::size_t disjoint = 0, below = 0;
    const double inf = std::numeric_limits<double>::infinity();
    for (const auto &p : pairs)
    {
        if (hcd::trianglesIntersect(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2]))
            continue;
        ++disjoint;
        const double d = hcd::disjointTriangleDistance(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2]);
        for (const double best : {inf, d, std::nextafter(d, inf), std::nextafter(d, -inf), d * (1 + 1e-12),
                                  d * (1 - 1e-12), 0.5 * d, 1.01 * d, 2.0 * d, 0.0})
        {
            below += best < d ? 1 : 0;
            ASSERT_EQ(hcd::disjointTriangleDistanceBelow(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2], best),
                      std::min(best, d))
                << "distance " << d << ", best " << best;
        }
    }
    EXPECT_GT(disjoint, 6000u);
    EXPECT_GT(below, 20000u);
}

// Non-finite input (a NaN corner, coordinates whose squares overflow, a NaN best): the pruned
// distance is still the minimum of its best and the full distance, NaN exactly where that is.
TEST(TriangleDistance, DistanceBelowKeepsTheMinimumOnNonFiniteInput)
{
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    const Triangle a = {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1)}, b = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    std::vector<std::array<Triangle, 2>> pairs = {{a, b}};
    Triangle withNan = a;
    withNan[0].x() = nan;
    pairs.push_back({withNan, b});
    Triangle huge = a;
    for (Vec3 &v : huge)
        v *= 1e200;
    pairs.push_back({huge, b});
    pairs.push_back({b, huge});
    const auto same = [](double x, double y) { return (std::isnan(x) && std::isnan(y)) || x == y; };
    for (const auto &p : pairs)
    {
        const double d = hcd::disjointTriangleDistance(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2]);
        for (const double best : {inf, nan, 0.5, 2.0, 0.0})
        {
            const double below =
                hcd::disjointTriangleDistanceBelow(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2], best);
            EXPECT_TRUE(same(below, std::min(best, d))) << "best " << best << ": " << below << " against " << d;
        }
    }
}

// Dense sampling: every sampled pair of points is at least the distance apart (less rounding), and
// the nearest sampled pair is within the sampling's resolution of it.
TEST(TriangleDistance, BracketsDenseSampling)
{
    hcd::test::TestRandom rng(hcd::test::seeded(2713));
    constexpr int kSteps = 24;
    const auto samples = [](const Triangle &t) {
        std::vector<Vec3> s;
        for (int i = 0; i <= kSteps; ++i)
            for (int j = 0; i + j <= kSteps; ++j)
                s.push_back(t[0] + (double(i) / kSteps) * (t[1] - t[0]) + (double(j) / kSteps) * (t[2] - t[0]));
        return s;
    };
    for (const auto &p : trianglePairs(1.0, 200, rng))
    {
        const double d = distanceOf(p);
        double nearest = std::numeric_limits<double>::infinity();
        const std::vector<Vec3> sa = samples(p[0]), sb = samples(p[1]);
        for (const Vec3 &u : sa)
            for (const Vec3 &v : sb)
                nearest = std::min(nearest, (u - v).norm());
        double longest = 0.0;
        for (const Triangle &t : p)
            for (int k = 0; k < 3; ++k)
                longest = std::max(longest, (t[std::size_t(k)] - t[std::size_t((k + 1) % 3)]).norm());
        EXPECT_LE(d, nearest + 1e-12);
        // Each triangle's samples lie within 2 longest / kSteps of its points.
        EXPECT_GE(d, nearest - 4.0 * longest / kSteps);
    }
}
}  // namespace
