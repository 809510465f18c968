// SPDX-License-Identifier: BSD-3-Clause
// Swept-sphere volumes: each kind's fit holds its points, the core distance matches a dense
// sampling of the two cores, and touching volumes are never called apart (random and adversarial
// cases: parallel segments, coplanar and degenerate rectangles, huge and tiny scales).
#include "support/test_support.h"

#include "hybridcd/bv/swept_sphere.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

using namespace hcd;

namespace
{
double uniform(test::TestRandom &rng, double lo, double hi)
{
    return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// Points of the core on a grid of `steps` + 1 per side.
std::vector<Vec3> coreSamples(const Ssv &s, int steps)
{
    std::vector<Vec3> points;
    const int nu = s.halfLength[0] > 0.0 ? steps : 0, nv = s.halfLength[1] > 0.0 ? steps : 0;
    for (int i = 0; i <= nu; ++i)
        for (int j = 0; j <= nv; ++j)
        {
            const double a = nu ? -1.0 + 2.0 * i / nu : 0.0, b = nv ? -1.0 + 2.0 * j / nv : 0.0;
            points.push_back(s.center + s.axes.col(0) * (a * s.halfLength[0]) + s.axes.col(1) * (b * s.halfLength[1]));
        }
    return points;
}

// The largest distance from a core point to its nearest grid sample.
double samplingError(const Ssv &s, int steps) { return std::hypot(s.halfLength[0], s.halfLength[1]) / steps; }

// A random core of the given kind at scale `scale`; `degenerate` gives a rectangle a zero side.
Ssv randomSsv(test::TestRandom &rng, Ssv::Kind kind, double scale, bool degenerate = false)
{
    Ssv s;
    s.kind = kind;
    s.center = scale * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    s.axes = test::randomRotation(rng);
    if (kind != Ssv::Kind::Point)
        s.halfLength[0] = scale * uniform(rng, 0.05, 1.0);
    if (kind == Ssv::Kind::Rectangle)
        s.halfLength[1] = degenerate ? 0.0 : scale * uniform(rng, 0.05, 1.0);
    s.radius = scale * uniform(rng, 0.0, 0.3);
    return s;
}

Vec3 randomCorePoint(test::TestRandom &rng, const Ssv &s)
{
    return s.center + s.axes.col(0) * (uniform(rng, -1, 1) * s.halfLength[0]) +
           s.axes.col(1) * (uniform(rng, -1, 1) * s.halfLength[1]);
}

const Ssv::Kind kKinds[] = {Ssv::Kind::Point, Ssv::Kind::Segment, Ssv::Kind::Rectangle};
}  // namespace

TEST(SweptSphere, EachKindHoldsItsPoints)
{
    test::TestRandom rng(test::seeded(3701));
    for (int trial = 0; trial < test::cases(600); ++trial)
    {
        const double scale = std::pow(10.0, double(trial % 13) - 6.0);  // 1e-6 .. 1e6
        const Vec3 offset = scale * Vec3(uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -3, 3));
        const Mat3 r = test::randomRotation(rng);
        // Blob, flat patch, needle, collinear, a single repeated point.
        const int shape = trial % 5;
        const Vec3 stretch = shape == 0   ? Vec3(1, 0.7, 0.5)
                             : shape == 1 ? Vec3(1, 0.8, 0)
                             : shape == 2 ? Vec3(1, 0.02, 0.02)
                             : shape == 3 ? Vec3(1, 0, 0)
                                          : Vec3(0, 0, 0);
        std::vector<Vec3> points(1 + std::size_t(rng() % 40));
        for (Vec3 &p : points)
            p = offset +
                scale * (r * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)).cwiseProduct(stretch));
        for (const Ssv::Kind kind : kKinds)
        {
            const Ssv s = Ssv::fitKind(points, kind);
            ASSERT_EQ(s.kind, kind);
            for (const Vec3 &p : points)
                ASSERT_TRUE(s.contains(p)) << "kind " << int(kind) << ", trial " << trial;
        }
        const Ssv best = Ssv::fit(points);
        for (const Ssv::Kind kind : kKinds)
            EXPECT_LE(best.volume(), Ssv::fitKind(points, kind).volume()) << "the smallest kind is kept";
        for (const Vec3 &p : points)
            ASSERT_TRUE(best.contains(p)) << trial;
    }
}

TEST(SweptSphere, ShapesGetTheirKind)
{
    // A needle is a capsule, a thin plate a rectangle, a round cloud a sphere.
    test::TestRandom rng(test::seeded(3702));
    std::vector<Vec3> needle, plate, ball;
    for (int i = 0; i < 200; ++i)
    {
        needle.push_back(Vec3(uniform(rng, -1, 1), 0.01 * uniform(rng, -1, 1), 0.01 * uniform(rng, -1, 1)));
        plate.push_back(Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), 0.01 * uniform(rng, -1, 1)));
        Vec3 d(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
        ball.push_back(d.normalized());
    }
    EXPECT_EQ(Ssv::fit(needle).kind, Ssv::Kind::Segment);
    EXPECT_EQ(Ssv::fit(plate).kind, Ssv::Kind::Rectangle);
    EXPECT_EQ(Ssv::fit(ball).kind, Ssv::Kind::Point);
    EXPECT_LT(Ssv::fit(plate).radius, 0.02);
}

TEST(SweptSphere, CoreDistanceMatchesDenseSampling)
{
    test::TestRandom rng(test::seeded(3703));
    const int steps = 40;
    int apart = 0, overlapping = 0;
    for (int trial = 0; trial < test::cases(900); ++trial)
    {
        const double scale = std::pow(10.0, double(trial % 5) * 2.0 - 4.0);
        const Ssv a = randomSsv(rng, kKinds[trial % 3], scale, trial % 7 == 0);
        Ssv b = randomSsv(rng, kKinds[(trial / 3) % 3], scale, trial % 11 == 0);
        if (trial % 4 == 0)
            b.axes = a.axes;  // parallel cores
        double sampled = std::numeric_limits<double>::infinity();
        for (const Vec3 &p : coreSamples(a, steps))
            for (const Vec3 &q : coreSamples(b, steps))
                sampled = std::min(sampled, (p - q).norm());
        const double error = samplingError(a, steps) + samplingError(b, steps);
        const double core = ssvGap(a, b) + a.radius + b.radius;
        // Sampled points lie on the cores, so the exact distance is at most theirs; and every core
        // point is within the sampling error of a sample.
        EXPECT_LE(core, sampled * (1 + 1e-12) + 1e-12 * scale) << trial;
        EXPECT_GE(core, sampled - error - 1e-12 * scale) << trial;
        const double tolerance = 1e-10 * scale;
        const double gapLow = sampled - error - a.radius - b.radius;
        if (gapLow > tolerance)
        {
            EXPECT_FALSE(ssvsOverlap(a, b, tolerance)) << "needlessly conservative, trial " << trial;
            EXPECT_GE(ssvDistanceLowerBound(a, b, tolerance), 0.0);
            ++apart;
        }
        if (sampled - a.radius - b.radius <= 0.0)
        {
            EXPECT_TRUE(ssvsOverlap(a, b, tolerance)) << trial;
            EXPECT_EQ(ssvDistanceLowerBound(a, b, tolerance), 0.0) << trial;
            ++overlapping;
        }
        EXPECT_LE(ssvDistanceLowerBound(a, b, tolerance), std::max(0.0, sampled - a.radius - b.radius)) << trial;
    }
    EXPECT_GT(apart, test::cases(900) / 10);
    EXPECT_GT(overlapping, test::cases(900) / 10);
}

// Volumes placed to touch at one point: b's core point q is put at distance ra + rb from a's core
// point p. Their contents share a point (or more, when other core points come closer), so the
// test must say "overlap" with only the rounding tolerance.
TEST(SweptSphere, TouchingVolumesAreNeverRejected)
{
    test::TestRandom rng(test::seeded(3704));
    int cases = 0;
    for (int trial = 0; trial < test::cases(6000); ++trial)
    {
        const double scale = std::pow(10.0, double(trial % 13) - 6.0);
        const int shape = (trial / 13) % 6;
        Ssv a = randomSsv(rng, kKinds[trial % 3], scale, shape == 1);
        Ssv b = randomSsv(rng, kKinds[(trial / 3) % 3], scale, shape == 2);
        if (shape == 3 || shape == 4)
            b.axes = a.axes;  // parallel segments, coplanar or stacked rectangles
        if (shape == 5)
            b.radius = a.radius = 0.0;  // bare cores touching
        const Vec3 p = randomCorePoint(rng, a);
        Vec3 n;
        if (shape == 4)
            n = a.axes.col(2);  // stacked along the common normal
        else if (shape == 3)
            n = a.axes.col(0);  // end to end along the common axis
        else
            n = test::randomRotation(rng).col(0);
        const Vec3 q = randomCorePoint(rng, b);
        b.center += p + n * (a.radius + b.radius) - q;
        const double tolerance = 1e-10 * (scale + b.center.norm() + a.center.norm());
        ASSERT_TRUE(ssvsOverlap(a, b, tolerance)) << "trial " << trial << ", shape " << shape;
        ASSERT_TRUE(ssvsOverlap(b, a, tolerance)) << "trial " << trial << ", shape " << shape;
        EXPECT_EQ(ssvDistanceLowerBound(a, b, tolerance), 0.0) << trial;
        ++cases;
    }
    EXPECT_EQ(cases, test::cases(6000));
}

TEST(SweptSphere, PlacementKeepsDistances)
{
    // A rigid motion of both volumes changes no gap (beyond rounding).
    test::TestRandom rng(test::seeded(3705));
    for (int trial = 0; trial < test::cases(500); ++trial)
    {
        const Ssv a = randomSsv(rng, kKinds[trial % 3], 1.0), b = randomSsv(rng, kKinds[(trial / 3) % 3], 1.0);
        const RigidTransform pose{test::randomRotation(rng),
                                  Vec3(uniform(rng, -100, 100), uniform(rng, -100, 100), uniform(rng, -100, 100))};
        EXPECT_NEAR(ssvGap(a.transformed(pose), b.transformed(pose)), ssvGap(a, b), 1e-9) << trial;
    }
}
