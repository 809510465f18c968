// SPDX-License-Identifier: BSD-3-Clause
// The triangle pair's fifteen features in SIMD lanes (geometry/triangle_features.h): the same bits
// as the scalar reference under every instruction set compiled in, on random, nearly coplanar,
// lattice, sliver, degenerate (segment and point) and far-out triangles at scales 1e-9 to 1e80; the
// reference against an independent formulation (the closest point on the triangle by its Voronoi
// regions, and the segments' closest points) within rounding; and, with the public segment
// distance of triangle_distance.h, against the exact distance in rational arithmetic where edges
// are nearly parallel.
#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_features.h"
#include "hybridcd/geometry/triangle_intersection.h"

#include "support/test_support.h"

#include <boost/multiprecision/cpp_int.hpp>
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

// ---------------------------------------------------------------------------------------------
// Exact squared distances in rational arithmetic (every double is a rational).
using Rational = boost::multiprecision::cpp_rational;

struct RVec
{
    Rational x, y, z;
};
RVec exact(const Vec3 &v) { return {Rational(v.x()), Rational(v.y()), Rational(v.z())}; }
RVec operator-(const RVec &a, const RVec &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
RVec operator+(const RVec &a, const RVec &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
RVec operator*(const RVec &a, const Rational &k) { return {a.x * k, a.y * k, a.z * k}; }
Rational dot(const RVec &a, const RVec &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
RVec cross(const RVec &a, const RVec &b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Rational clampUnit(const Rational &x) { return x < 0 ? Rational(0) : (x > 1 ? Rational(1) : x); }

// Closed segments p0p1 and q0q1: the least of the convex |r + s d1 - t d2|^2 over the unit square
// lies at its critical point or on an edge of the square, each edge's least at a clamped one.
Rational exactSegmentsSquared(const RVec &p0, const RVec &p1, const RVec &q0, const RVec &q1)
{
    const RVec d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const Rational a = dot(d1, d1), e = dot(d2, d2), b = dot(d1, d2), c = dot(d1, r), f = dot(d2, r);
    const auto at = [&](const Rational &s, const Rational &t) {
        const RVec g = r + d1 * s - d2 * t;
        return dot(g, g);
    };
    Rational best = at(0, 0);
    for (int side = 0; side < 2; ++side)
    {
        const Rational fixed(side);
        best = std::min(best, at(fixed, e > 0 ? clampUnit((f + fixed * b) / e) : Rational(0)));
        best = std::min(best, at(a > 0 ? clampUnit((fixed * b - c) / a) : Rational(0), fixed));
    }
    const Rational denom = a * e - b * b;
    if (denom > 0)
    {
        const Rational s = (b * f - c * e) / denom;
        const Rational t = (f + s * b) / e;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1)
            best = std::min(best, at(s, t));
    }
    return best;
}

// A point and a closed triangle: to its plane where it projects inside, else to its edges.
Rational exactPointTriangleSquared(const RVec &p, const RVec (&t)[3])
{
    Rational best = exactSegmentsSquared(p, p, t[0], t[1]);
    best = std::min(best, exactSegmentsSquared(p, p, t[1], t[2]));
    best = std::min(best, exactSegmentsSquared(p, p, t[2], t[0]));
    const RVec n = cross(t[1] - t[0], t[2] - t[0]);
    const Rational nn = dot(n, n);
    bool inside = nn > 0;
    for (int k = 0; k < 3 && inside; ++k)
        inside = dot(cross(t[(k + 1) % 3] - t[k], p - t[k]), n) >= 0;
    if (inside)
    {
        const Rational h = dot(n, p - t[0]);
        best = std::min(best, Rational(h * h / nn));
    }
    return best;
}

Rational exactDisjointSquared(const Pair &pair)
{
    RVec x[2][3];
    for (int s = 0; s < 2; ++s)
        for (int k = 0; k < 3; ++k)
            x[s][k] = exact(pair[std::size_t(s)][std::size_t(k)]);
    Rational best = exactPointTriangleSquared(x[0][0], x[1]);
    for (int s = 0; s < 2; ++s)
        for (int k = 0; k < 3; ++k)
            best = std::min(best, exactPointTriangleSquared(x[s][k], x[1 - s]));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            best = std::min(best, exactSegmentsSquared(x[0][i], x[0][(i + 1) % 3], x[1][j], x[1][(j + 1) % 3]));
    return best;
}

// Triangles whose nearest features are two edges 1e-6 to 1e-13 from parallel, at scales 1e-3 to
// 1e3, beside general ones; the features (reference and lanes alike) within 1e-13 of the scale of
// the exact distance. Ericson's (b f - c e) / (a e - b^2) missed by up to 5e-10 on unit edges here
// (the first pair below: exact 7.07e-13).
TEST(TriangleFeatures, NearlyParallelEdgesAgainstExactRationals)
{
    hcd::test::TestRandom rng(hcd::test::seeded(2903));
    std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(6.0, 13.0);
    std::vector<Pair> pairs = {
        {Triangle{Vec3(-0.5, 0, 0), Vec3(0.5, 0, 0), Vec3(0, -1, 0)},
         Triangle{Vec3(-0.5, -5e-10, 1e-12 + 5e-10), Vec3(0.5, 5e-10, 1e-12 - 5e-10), Vec3(0, 1, 1)}}};
    const auto point = [&] { return Vec3(unit(rng), unit(rng), unit(rng)); };
    for (const double scale : {1e-3, 1.0, 1e3})
        for (int i = 0; i < 400; ++i)
        {
            const Vec3 a0 = point(), a1 = point(), away = point().normalized();
            const Vec3 gap = std::pow(10.0, -angle(rng)) * point();  // a tiny offset, then a tiny turn
            const double tilt = std::pow(10.0, -angle(rng));
            const Vec3 b0 = a0 + gap + tilt * point(), b1 = a1 + gap + tilt * point();
            Triangle a = {a0, a1, 0.5 * (a0 + a1) - away}, b = {b1, b0, 0.5 * (a0 + a1) + away};
            for (Triangle *t : {&a, &b})
                for (Vec3 &v : *t)
                    v *= scale;
            pairs.push_back({a, b});
        }
    std::size_t checked = 0;
    for (const Pair &p : pairs)
    {
        if (hcd::trianglesIntersect(p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2]))
            continue;
        ++checked;
        double scale = 0.0;
        for (const Triangle &t : p)
            for (const Vec3 &v : t)
                scale = std::max(scale, v.cwiseAbs().maxCoeff());
        const double truth = std::sqrt(exactDisjointSquared(p).convert_to<double>());
        ASSERT_NEAR(std::sqrt(reference(p)), truth, 1e-13 * scale) << "pair " << checked;
        ASSERT_NEAR(std::sqrt(lanes(p)), truth, 1e-13 * scale) << "pair " << checked;
    }
    EXPECT_GT(checked, 300u);
}

// The public segment distance (capsules, swept spheres) on segments 1e-6 to 1e-13 from parallel,
// crossing or just apart, against the exact distance: to 1e-13 of the scale.
TEST(SegmentDistance, NearlyParallelSegmentsAgainstExactRationals)
{
    hcd::test::TestRandom rng(hcd::test::seeded(2904));
    std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(6.0, 13.0);
    const auto point = [&] { return Vec3(unit(rng), unit(rng), unit(rng)); };
    int checked = 0;
    for (const double scale : {1e-3, 1.0, 1e3})
        for (int i = 0; i < 400; ++i)
        {
            const Vec3 p0 = scale * point(), p1 = scale * point();
            const Vec3 gap = scale * std::pow(10.0, -angle(rng)) * point();
            const double tilt = scale * std::pow(10.0, -angle(rng));
            const Vec3 q0 = p0 + gap + tilt * point(), q1 = p1 + gap + tilt * point();
            const double magnitude = std::max({p0.cwiseAbs().maxCoeff(), p1.cwiseAbs().maxCoeff(),
                                               q0.cwiseAbs().maxCoeff(), q1.cwiseAbs().maxCoeff()});
            const double truth =
                std::sqrt(exactSegmentsSquared(exact(p0), exact(p1), exact(q0), exact(q1)).convert_to<double>());
            ASSERT_NEAR(std::sqrt(hcd::segmentSegmentDistanceSquared(p0, p1, q0, q1)), truth, 1e-13 * magnitude)
                << "segment pair " << checked;
            ++checked;
        }
    EXPECT_EQ(checked, 1200);
}
}  // namespace
