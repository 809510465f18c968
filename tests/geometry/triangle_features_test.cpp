// SPDX-License-Identifier: BSD-3-Clause
// The triangle pair's fifteen features in SIMD lanes (geometry/triangle_features.h): the same bits
// as the scalar reference under every instruction set compiled in, on random, nearly coplanar,
// lattice, sliver, degenerate (segment and point) and far-out triangles at scales 1e-9 to 1e80; and
// the reference against an independent formulation (the closest point on the triangle by its
// Voronoi regions, and the segments' closest points) within rounding.
#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_features.h"
#include "hybridcd/geometry/triangle_intersection.h"

#include "support/test_support.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace
{
using hcd::Vec3;
using Triangle = std::array<Vec3, 3>;
using Pair = std::array<Triangle, 2>;

Pair randomPair(hcd::test::TestRandom &rng, double scale)
{
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> lattice(-2, 2);
    const auto point = [&] { return Vec3(unit(rng), unit(rng), unit(rng)); };
    Triangle a = {point(), point(), point()}, b = {point() + Vec3(0.8, 0, 0), point(), point()};
    switch (rng() % 7)
    {
    case 0:
        break;
    case 1:  // nearly coplanar: b a shifted, slightly tilted copy of a, reversed
        for (int k = 0; k < 3; ++k)
            b[std::size_t(k)] = a[std::size_t(2 - k)] + 1e-3 * Vec3(0.3, -0.2, 0.5) + 1e-9 * point();
        break;
    case 2:  // a lattice: shared vertices, touching edges, parallel edges
        for (Triangle *t : {&a, &b})
            for (Vec3 &v : *t)
                v = 0.5 * Vec3(lattice(rng), lattice(rng), lattice(rng));
        break;
    case 3:  // slivers: a third corner within 1e-9 of the first edge
        for (Triangle *t : {&a, &b})
            (*t)[2] = 0.5 * ((*t)[0] + (*t)[1]) + 1e-9 * point();
        break;
    case 4:  // degenerate: a segment (two corners equal) and a point
        a[2] = a[0];
        if (rng() % 2 == 0)
            b[1] = b[2] = b[0];
        break;
    case 5:  // collinear corners, and parallel edges across the pair
        a[2] = a[0] + 0.37 * (a[1] - a[0]);
        b = {a[0] + Vec3(0, 0, 0.25), a[1] + Vec3(0, 0, 0.25), b[2]};
        break;
    default:  // tiny triangles far out
        for (Triangle *t : {&a, &b})
            for (Vec3 &v : *t)
                v = Vec3(3e6, -2e6, 1e6) + 1e-3 * v;
        break;
    }
    for (Triangle *t : {&a, &b})
        for (Vec3 &v : *t)
            v *= scale;
    return {a, b};
}

std::vector<Pair> pairsAtEveryScale(std::uint64_t seed)
{
    hcd::test::TestRandom rng(hcd::test::seeded(seed));
    std::vector<Pair> pairs;
    for (const double scale : {1e-9, 1e-3, 1.0, 1e3, 1e9, 1e70, 1e80})
        for (int i = 0; i < 2000; ++i)
            pairs.push_back(randomPair(rng, scale));
    return pairs;
}

double lanes(const Pair &p)
{
    return hcd::triangleFeaturesSquared(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2]);
}

double reference(const Pair &p)
{
    return hcd::triangleFeaturesSquaredReference(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2]);
}

TEST(TriangleFeatures, LanesAreTheReferenceBitForBitUnderEveryInstructionSet)
{
    const std::vector<Pair> pairs = pairsAtEveryScale(2901);
    int targets = 0;
    for (const std::int64_t target : hwy::SupportedAndGeneratedTargets())
    {
        SCOPED_TRACE(hwy::TargetName(target));
        hwy::SetSupportedTargetsForTest(target);
        ++targets;
        for (std::size_t i = 0; i < pairs.size(); ++i)
        {
            const double fast = lanes(pairs[i]), slow = reference(pairs[i]);
            ASSERT_TRUE(fast == slow || (std::isnan(fast) && std::isnan(slow)))
                << "pair " << i << ": " << fast << " against " << slow;
        }
        hwy::SetSupportedTargetsForTest(0);
    }
    EXPECT_GE(targets, 2);  // at least the baseline and one wider set on any x86-64 machine
}

// Non-finite corners take the reference's own path, so they agree too.
TEST(TriangleFeatures, NonFiniteCornersGiveTheReferenceValue)
{
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    Pair p = {Triangle{Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1)},
              Triangle{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}};
    EXPECT_EQ(lanes(p), 1.0);
    for (const double bad : {nan, inf, -inf})
    {
        Pair q = p;
        q[1][2].y() = bad;
        const double fast = lanes(q), slow = reference(q);
        EXPECT_TRUE(fast == slow || (std::isnan(fast) && std::isnan(slow))) << fast << " against " << slow;
    }
}

// An independent formulation: each vertex's closest point on the other triangle by its Voronoi
// regions, and the edges' closest points.
double independentSquared(const Pair &p)
{
    double best = std::numeric_limits<double>::infinity();
    for (int s = 0; s < 2; ++s)
    {
        const Triangle &x = p[std::size_t(s)], &y = p[std::size_t(1 - s)];
        for (const Vec3 &v : x)
            best = std::min(best, (v - hcd::closestPointOnTriangle(v, y[0], y[1], y[2])).squaredNorm());
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            best = std::min(best,
                            hcd::segmentSegmentDistanceSquared(p[0][std::size_t(i)], p[0][std::size_t((i + 1) % 3)],
                                                               p[1][std::size_t(j)], p[1][std::size_t((j + 1) % 3)]));
    return best;
}

TEST(TriangleFeatures, ReferenceIsTheDistanceOfAnIndependentFormulation)
{
    std::size_t disjoint = 0;
    for (const Pair &p : pairsAtEveryScale(2902))
    {
        double scale = 0.0;
        for (const Triangle &t : p)
            for (const Vec3 &v : t)
                scale = std::max(scale, v.cwiseAbs().maxCoeff());
        if (scale > 1e75 || hcd::trianglesIntersect(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2]))
            continue;  // (beyond 1e77 both formulations' products of four coordinates overflow)
        ++disjoint;
        const double features = std::sqrt(reference(p)), independent = std::sqrt(independentSquared(p));
        ASSERT_NEAR(features, independent, 1e-12 * scale) << "scale " << scale;
    }
    EXPECT_GT(disjoint, 7000u);
}
}  // namespace
