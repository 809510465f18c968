// SPDX-License-Identifier: BSD-3-Clause
// Section 5 of the review: the time of contact of a translating piece (the LP with time as a
// fourth variable), the penetration depth vector and the directional penetration depth. Checked
// against analytic answers (boxes per axis interval, tetrahedra by vertex-face and edge-edge
// events), against the static narrow phase on a fine grid of times and on the swept hull (a
// convex piece translating over [0, T] meets a fixed one exactly when the hull of its two end
// positions does), and against a brute-force search over a dense sphere of directions.
#include "hybridcd/narrowphase/convex_piece.h"
#include "hybridcd/narrowphase/linear_program.h"
#include "hybridcd/narrowphase/penetration.h"
#include "hybridcd/narrowphase/time_of_contact.h"
#include "support/test_support.h"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

namespace hcd
{
namespace
{
using test::TestRandom;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Point sets, pieces and poses.

double uniform(TestRandom &rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

Vec3 randomInBall(TestRandom &rng)
{
    for (;;)
    {
        const Vec3 p(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
        if (p.squaredNorm() <= 1.0)
            return p;
    }
}

Vec3 randomUnit(TestRandom &rng)
{
    std::normal_distribution<double> n;
    for (;;)
    {
        const Vec3 v(n(rng), n(rng), n(rng));
        if (v.norm() > 1e-3)
            return v.normalized();
    }
}

// `count` points in the unit ball stretched per axis by [0.3, 1], times `scale`.
std::vector<Vec3> randomCloud(TestRandom &rng, int count, double scale)
{
    const Vec3 axes(uniform(rng, 0.3, 1.0), uniform(rng, 0.3, 1.0), uniform(rng, 0.3, 1.0));
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i)
        points.push_back(scale * randomInBall(rng).cwiseProduct(axes));
    return points;
}

std::vector<Vec3> boxCorners(const Vec3 &lo, const Vec3 &hi)
{
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    return corners;
}

std::vector<Vec3> mapped(std::vector<Vec3> points, const RigidTransform &pose)
{
    for (Vec3 &p : points)
        p = pose.apply(p);
    return points;
}

ConvexPiece translated(const ConvexPiece &piece, const Vec3 &offset)
{
    return piece.transformed({Mat3::Identity(), offset});
}

double pairMagnitude(const ConvexPiece &a, const ConvexPiece &b) { return std::max(a.magnitude(), b.magnitude()); }

// The hull of the piece at times 0 and t of its translation: the region it sweeps.
ConvexPiece sweptHull(const ConvexPiece &piece, const Vec3 &displacement)
{
    std::vector<Vec3> points = piece.vertices;
    for (const Vec3 &v : piece.vertices)
        points.push_back(v + displacement);
    return ConvexPiece::hullOf(points);
}

double seconds(std::chrono::steady_clock::time_point since)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// The LP's witness lies in both pieces at its time.
void expectWitness(const TimeOfContact &toc, const ConvexPiece &moving, const Vec3 &displacement,
                   const ConvexPiece &fixed)
{
    const double tolerance = 1e-9 * (pairMagnitude(moving, fixed) + displacement.norm());
    EXPECT_LE(fixed.maxViolation(toc.point), tolerance);
    EXPECT_LE(moving.maxViolation(toc.point - toc.time * displacement), tolerance);
}

// ---------------------------------------------------------------------------------------------
// Analytic times of contact.

// First t in [0, 1] at which the box [lo1, hi1] + t v meets [lo2, hi2] (closed boxes), or +inf.
// Also reports how well conditioned the answer is: the moving box's speed along the axis whose
// interval opens last (the contact normal), relative to |v|.
double boxTimeOfContact(const Vec3 &lo1, const Vec3 &hi1, const Vec3 &v, const Vec3 &lo2, const Vec3 &hi2,
                        double *normalSpeed = nullptr)
{
    double enter = 0.0, exit = 1.0, speed = 1.0;
    for (int i = 0; i < 3; ++i)
    {
        // lo1 + t v <= hi2 and hi1 + t v >= lo2.
        if (v[i] == 0.0)
        {
            if (lo1[i] > hi2[i] || hi1[i] < lo2[i])
                return kInfinity;
            continue;
        }
        const double a = (hi2[i] - lo1[i]) / v[i], b = (lo2[i] - hi1[i]) / v[i];
        const double lo = std::min(a, b), hi = std::max(a, b);
        if (lo > enter)
            enter = lo, speed = std::fabs(v[i]) / v.norm();
        exit = std::min(exit, hi);
    }
    if (normalSpeed)
        *normalSpeed = enter > 0.0 ? speed : 1.0;
    return enter <= exit ? enter : kInfinity;
}

// A tetrahedron's four outward face planes n . x <= d (not normalised), built from its corners.
struct Tetrahedron
{
    std::array<Vec3, 4> corners;
    std::array<Vec3, 4> normals;
    std::array<double, 4> offsets;

    explicit Tetrahedron(const std::array<Vec3, 4> &c) : corners(c)
    {
        static const int faces[4][4] = {{1, 2, 3, 0}, {0, 2, 3, 1}, {0, 1, 3, 2}, {0, 1, 2, 3}};
        for (int f = 0; f < 4; ++f)
        {
            const Vec3 &p = c[faces[f][0]];
            Vec3 n = (c[faces[f][1]] - p).cross(c[faces[f][2]] - p);
            if (n.dot(c[faces[f][3]] - p) > 0.0)
                n = -n;
            normals[f] = n;
            offsets[f] = n.dot(p);
        }
    }

    double volume() const
    {
        return std::fabs((corners[1] - corners[0]).cross(corners[2] - corners[0]).dot(corners[3] - corners[0])) / 6.0;
    }
};

// First t in [0, 1] at which p + t w lies in the tetrahedron (clipping the ray against its face
// planes), or +inf. `rate` receives the speed at which the entering plane is crossed.
double rayEntry(const Vec3 &p, const Vec3 &w, const Tetrahedron &t, double *rate)
{
    double enter = 0.0, exit = 1.0;
    *rate = kInfinity;
    for (int f = 0; f < 4; ++f)
    {
        const double s = t.normals[f].dot(w), slack = t.offsets[f] - t.normals[f].dot(p);
        if (s == 0.0)
        {
            if (slack < 0.0)
                return kInfinity;
            continue;
        }
        const double bound = slack / s;
        if (s > 0.0)
            exit = std::min(exit, bound);
        else if (bound > enter)
            enter = bound, *rate = -s / (t.normals[f].norm() * w.norm());
    }
    return enter <= exit ? enter : kInfinity;
}

// First contact of tetrahedron m translating by v with the fixed tetrahedron f, both disjoint at
// t = 0: the earliest vertex-face event (a vertex of one entering the other) or edge-edge event
// (an edge of one crossing an edge of the other), or +inf. `condition` receives the event's
// normal speed relative to |v| (small for grazing contacts, whose time is ill-conditioned).
double tetrahedraTimeOfContact(const Tetrahedron &m, const Vec3 &v, const Tetrahedron &f, double *condition)
{
    double best = kInfinity, rate = 0.0;
    *condition = 1.0;
    for (const Vec3 &p : m.corners)
    {
        const double t = rayEntry(p, v, f, &rate);
        if (t < best)
            best = t, *condition = rate;
    }
    for (const Vec3 &q : f.corners)
    {
        const double t = rayEntry(q, -v, m, &rate);
        if (t < best)
            best = t, *condition = rate;
    }
    static const int edges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    for (const auto &em : edges)
        for (const auto &ef : edges)
        {
            // p0 + s (p1 - p0) + t v = q0 + r (q1 - q0), s and r in [0, 1].
            const Vec3 p0 = m.corners[em[0]], dm = m.corners[em[1]] - p0;
            const Vec3 q0 = f.corners[ef[0]], df = f.corners[ef[1]] - q0;
            Mat3 system;
            system << dm, -df, v;
            const Vec3 normal = dm.cross(df);
            const double normalRate = std::fabs(normal.dot(v)) / (normal.norm() * v.norm());
            if (!(normalRate > 1e-6))
                continue;  // parallel edges, or motion within their plane: other events cover it
            const Vec3 srt = system.fullPivLu().solve(q0 - p0);
            if (srt[0] >= 0.0 && srt[0] <= 1.0 && srt[1] >= 0.0 && srt[1] <= 1.0 && srt[2] >= 0.0 && srt[2] < best)
                best = srt[2], *condition = normalRate;
        }
    return best <= 1.0 ? best : kInfinity;
}

// ---------------------------------------------------------------------------------------------
// Time of contact.

TEST(TimeOfContact, BoxesAgainstAnalyticAnswer)
{
    TestRandom rng(501);
    int contacts = 0, atStart = 0, misses = 0, ambiguous = 0;
    double worstError = 0.0, worstConditioned = 0.0;
    const auto start = std::chrono::steady_clock::now();
    const int cases = 3000;
    for (int i = 0; i < cases; ++i)
    {
        const double scale = i % 3 == 0 ? 1.0 : (i % 3 == 1 ? 1e3 : 1e-3);
        const Vec3 lo2 = scale * Vec3(uniform(rng, -1, 0), uniform(rng, -1, 0), uniform(rng, -1, 0));
        const Vec3 hi2 = lo2 + scale * Vec3(uniform(rng, 0.2, 2), uniform(rng, 0.2, 2), uniform(rng, 0.2, 2));
        const Vec3 size1 = scale * Vec3(uniform(rng, 0.2, 2), uniform(rng, 0.2, 2), uniform(rng, 0.2, 2));
        const Vec3 v = scale * uniform(rng, 0.5, 6.0) * randomUnit(rng);
        // Start so that the centre passes near the fixed box at a random fraction of the step.
        const Vec3 centre1 = 0.5 * (lo2 + hi2) - uniform(rng, -0.3, 1.3) * v + scale * 1.5 * randomInBall(rng);
        const Vec3 lo1 = centre1 - 0.5 * size1, hi1 = centre1 + 0.5 * size1;

        double speed = 1.0;
        const double expected = boxTimeOfContact(lo1, hi1, v, lo2, hi2, &speed);
        // Contact that only just happens or just fails (within 1e-9 of the step) is a coin toss.
        if (std::isinf(expected))
        {
            const double t1 =
                boxTimeOfContact(lo1 - Vec3::Constant(1e-9 * scale), hi1 + Vec3::Constant(1e-9 * scale), v, lo2, hi2);
            if (!std::isinf(t1))
            {
                ++ambiguous;
                continue;
            }
        }

        // The same configuration in a random pose (the answer is invariant).
        // (far from the origin for some: coordinates up to 1000 times the boxes' size)
        const double distance = std::pow(10.0, uniform(rng, 0.0, 3.0));
        const RigidTransform pose{test::randomRotation(rng), scale * distance * randomInBall(rng)};
        const ConvexPiece moving = ConvexPiece::hullOf(mapped(boxCorners(lo1, hi1), pose));
        const ConvexPiece fixed = ConvexPiece::hullOf(mapped(boxCorners(lo2, hi2), pose));
        const Vec3 displacement = pose.rotation * v;
        const TimeOfContact toc = translationalTimeOfContact(moving, displacement, fixed);

        if (std::isinf(expected))
        {
            ++misses;
            EXPECT_FALSE(toc.contact) << "case " << i << ": LP time " << toc.time;
            continue;
        }
        ++contacts;
        atStart += expected == 0.0;
        ASSERT_TRUE(toc.contact) << "case " << i << ": expected time " << expected;
        const double error = std::fabs(toc.time - expected);
        worstError = std::max(worstError, error);
        if (speed > 1e-3)
            worstConditioned = std::max(worstConditioned, error);
        // The error bound scales with the contact's conditioning (1 / normal speed).
        EXPECT_LE(error, 1e-9 * std::max(1.0, 1e-2 / speed))
            << "case " << i << ": expected " << expected << ", normal speed " << speed;
        expectWitness(toc, moving, displacement, fixed);
    }
    std::printf("[boxes] %d cases: %d contacts (%d at the start), %d misses, %d skipped as ambiguous; worst time "
                "error %.3g (%.3g with normal speed > 1e-3); %.1f us/case including hulls\n",
                cases, contacts, atStart, misses, ambiguous, worstError, worstConditioned,
                1e6 * seconds(start) / cases);
    EXPECT_GT(contacts, cases / 4);
    EXPECT_GT(misses, cases / 10);
    EXPECT_GT(atStart, cases / 50);
    EXPECT_LT(worstConditioned, 1e-9);
}

TEST(TimeOfContact, TetrahedraAgainstAnalyticAnswer)
{
    TestRandom rng(502);
    int contacts = 0, misses = 0, skipped = 0, atStart = 0;
    double worstError = 0.0;
    const int cases = 3000;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < cases; ++i)
    {
        const double scale = i % 2 == 0 ? 1.0 : 1e2;
        std::array<Vec3, 4> cf, cm;
        for (Vec3 &c : cf)
            c = scale * randomInBall(rng);
        const Vec3 v = scale * uniform(rng, 1.0, 4.0) * randomUnit(rng);
        const Vec3 offset = -uniform(rng, 0.0, 1.2) * v + scale * 0.8 * randomInBall(rng);
        for (Vec3 &c : cm)
            c = offset + scale * randomInBall(rng);
        const Tetrahedron fixedTet(cf), movingTet(cm);
        if (fixedTet.volume() < 1e-3 * std::pow(scale, 3) || movingTet.volume() < 1e-3 * std::pow(scale, 3))
        {
            ++skipped;
            continue;
        }
        const ConvexPiece fixed = ConvexPiece::hullOf({cf.begin(), cf.end()});
        const ConvexPiece moving = ConvexPiece::hullOf({cm.begin(), cm.end()});
        const double gap0 = separatingAxisGap(moving, fixed);
        const double tolerance = 1e-9 * scale;
        double expected, condition = 1.0;
        if (gap0 < -tolerance)
            expected = 0.0;
        else if (gap0 > tolerance)
            expected = tetrahedraTimeOfContact(movingTet, v, fixedTet, &condition);
        else
        {
            ++skipped;
            continue;
        }
        // Only grazing by the end of the step, or an ill-conditioned grazing contact: skip.
        if (std::isinf(expected))
        {
            if (separatingAxisGap(sweptHull(moving, v), fixed) <= 1e-6 * scale)
            {
                ++skipped;
                continue;
            }
        }
        else if (condition < 1e-3)
        {
            ++skipped;
            continue;
        }

        const TimeOfContact toc = translationalTimeOfContact(moving, v, fixed);
        if (std::isinf(expected))
        {
            ++misses;
            EXPECT_FALSE(toc.contact) << "case " << i << ": LP time " << toc.time;
            continue;
        }
        ++contacts;
        atStart += expected == 0.0;
        ASSERT_TRUE(toc.contact) << "case " << i << ": expected " << expected;
        const double error = std::fabs(toc.time - expected);
        worstError = std::max(worstError, error);
        EXPECT_LE(error, 1e-9) << "case " << i << ": expected " << expected << ", condition " << condition;
        expectWitness(toc, moving, v, fixed);
    }
    std::printf("[tetrahedra] %d cases: %d contacts (%d at the start), %d misses, %d skipped (flat, touching or "
                "grazing); worst time error %.3g; %.1f us/case including hulls\n",
                cases, contacts, atStart, misses, skipped, worstError, 1e6 * seconds(start) / cases);
    EXPECT_GT(contacts, cases / 4);
    EXPECT_GT(misses, cases / 10);
    EXPECT_LT(skipped, cases / 4);
}

TEST(TimeOfContact, ExactCases)
{
    // Dyadic coordinates: every contact below is exact in floating point.
    const ConvexPiece unit = ConvexPiece::hullOf(boxCorners(Vec3(0, 0, 0), Vec3(1, 1, 1)));
    const ConvexPiece left = ConvexPiece::hullOf(boxCorners(Vec3(-3, 0.25, 0.5), Vec3(-2, 0.75, 1.5)));

    // Face against face exactly at the end of the step, halfway, and never.
    TimeOfContact toc = translationalTimeOfContact(left, Vec3(2, 0, 0), unit);
    ASSERT_TRUE(toc.contact);
    EXPECT_NEAR(toc.time, 1.0, 1e-12);
    expectWitness(toc, left, Vec3(2, 0, 0), unit);
    toc = translationalTimeOfContact(left, Vec3(4, 0, 0), unit);
    ASSERT_TRUE(toc.contact);
    EXPECT_NEAR(toc.time, 0.5, 1e-12);
    EXPECT_FALSE(translationalTimeOfContact(left, Vec3(1.99, 0, 0), unit).contact);
    // A near miss by 2^-26 (1.5e-8) of the size is no contact: only rounding-level gaps count.
    EXPECT_FALSE(translationalTimeOfContact(left, Vec3(2.0 - std::ldexp(1.0, -26), 0, 0), unit).contact);
    EXPECT_FALSE(
        translationalTimeOfContact(left, Vec3(2.0, 0, 0), translated(unit, Vec3(std::ldexp(1.0, -26), 0, 0))).contact);
    EXPECT_FALSE(translationalTimeOfContact(left, Vec3(-2, 0, 0), unit).contact);
    // Edge against edge exactly at the end: the box moved diagonally to meet along x = 0, z = 0.
    const ConvexPiece corner = ConvexPiece::hullOf(boxCorners(Vec3(-2, 0.25, -2), Vec3(-1, 0.75, -1)));
    toc = translationalTimeOfContact(corner, Vec3(1, 0, 1), unit);
    ASSERT_TRUE(toc.contact);
    EXPECT_NEAR(toc.time, 1.0, 1e-12);
    EXPECT_NEAR(toc.point.x(), 0.0, 1e-12);
    EXPECT_NEAR(toc.point.z(), 0.0, 1e-12);

    // Already intersecting, or touching, at t = 0: time 0 whatever the motion (even none).
    const ConvexPiece overlapping = ConvexPiece::hullOf(boxCorners(Vec3(0.5, 0.5, 0.5), Vec3(2, 2, 2)));
    for (const Vec3 &d : {Vec3(1, 2, 3), Vec3(-5, 0, 0), Vec3(0, 0, 0)})
    {
        toc = translationalTimeOfContact(overlapping, d, unit);
        ASSERT_TRUE(toc.contact);
        EXPECT_EQ(toc.time, 0.0);
        expectWitness(toc, overlapping, d, unit);
    }
    const ConvexPiece touching = ConvexPiece::hullOf(boxCorners(Vec3(1, 0, 0), Vec3(2, 1, 1)));
    toc = translationalTimeOfContact(touching, Vec3(3, 0, 0), unit);
    ASSERT_TRUE(toc.contact);
    EXPECT_EQ(toc.time, 0.0);
    EXPECT_FALSE(translationalTimeOfContact(left, Vec3(0, 0, 0), unit).contact);

    // A tetrahedron's apex hitting a face: the unit corner tetrahedron's face z = 0 at (1/4, 1/4).
    const ConvexPiece corner3 = ConvexPiece::hullOf({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)});
    const ConvexPiece spike =
        ConvexPiece::hullOf({Vec3(0.25, 0.25, -1), Vec3(-0.5, -0.5, -2), Vec3(1, -0.5, -2), Vec3(0.25, 1, -2)});
    toc = translationalTimeOfContact(spike, Vec3(0, 0, 1), corner3);
    ASSERT_TRUE(toc.contact);
    EXPECT_NEAR(toc.time, 1.0, 1e-12);
    EXPECT_NEAR((toc.point - Vec3(0.25, 0.25, 0)).norm(), 0.0, 1e-12);
    toc = translationalTimeOfContact(spike, Vec3(0, 0, 4), corner3);
    ASSERT_TRUE(toc.contact);
    EXPECT_NEAR(toc.time, 0.25, 1e-12);
    EXPECT_FALSE(translationalTimeOfContact(spike, Vec3(0, 0, 0.9990234375), corner3).contact);
    EXPECT_FALSE(translationalTimeOfContact(spike, Vec3(0, 0, 1.0 - std::ldexp(1.0, -26)), corner3).contact);
    // The same with the fixed piece the one that would move: the relative motion is what counts.
    toc = translationalTimeOfContact(corner3, Vec3(0, 0, -1), spike);
    ASSERT_TRUE(toc.contact);
    EXPECT_NEAR(toc.time, 1.0, 1e-12);

    // A flat square dropping onto the box, and a single point moving through it.
    const ConvexPiece square =
        ConvexPiece::hullOf({Vec3(0.25, 0.25, 3), Vec3(0.75, 0.25, 3), Vec3(0.75, 0.75, 3), Vec3(0.25, 0.75, 3)});
    toc = translationalTimeOfContact(square, Vec3(0, 0, -4), unit);
    ASSERT_TRUE(toc.contact);
    EXPECT_NEAR(toc.time, 0.5, 1e-12);
    const ConvexPiece point = ConvexPiece::hullOf({Vec3(0.5, -1, 0.5)});
    toc = translationalTimeOfContact(point, Vec3(0, 4, 0), unit);
    ASSERT_TRUE(toc.contact);
    EXPECT_NEAR(toc.time, 0.25, 1e-12);

    EXPECT_THROW(translationalTimeOfContact(unit, Vec3(kInfinity, 0, 0), left), std::invalid_argument);
}

// The LP against the static narrow phase. For a few pairs, literally on a grid of 10^4 steps:
// the LP time is no later than the first grid time at which the pieces intersect and no earlier
// than the last grid time before it at which they are disjoint. For many more pairs, the same
// by convexity: no contact over [0, t_k] (t_k the last grid time before the LP time, checked on
// the swept hull, which meets the fixed piece exactly when the motion does), intersecting at the
// LP time, and contact at all exactly when the swept hull over the whole step meets the piece.
TEST(TimeOfContact, AgreesWithStaticNarrowPhase)
{
    TestRandom rng(503);
    std::uniform_int_distribution<int> count(4, 24);
    const double step = 1e-4;
    const int gridSteps = 10000;
    int pairs = 0, contacts = 0, ambiguous = 0, gridPairs = 0, gridMisses = 0;
    double lpSeconds = 0.0;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < 3060; ++i)
    {
        const bool fullGrid = i < 60;
        const double scale = i % 3 == 0 ? 1.0 : (i % 3 == 1 ? 1e4 : 1e-4);
        const ConvexPiece fixed = ConvexPiece::hullOf(randomCloud(rng, count(rng), scale))
                                      .transformed({test::randomRotation(rng), Vec3::Zero()});
        const Vec3 v = scale * uniform(rng, 0.5, 5.0) * randomUnit(rng);
        const Vec3 startOffset = -uniform(rng, -0.2, 1.2) * v + scale * 1.2 * randomInBall(rng);
        const ConvexPiece moving = ConvexPiece::hullOf(randomCloud(rng, count(rng), scale))
                                       .transformed({test::randomRotation(rng), startOffset});
        const double tolerance = 1e-9 * (pairMagnitude(moving, fixed) + v.norm());

        const auto lpStart = std::chrono::steady_clock::now();
        const TimeOfContact toc = translationalTimeOfContact(moving, v, fixed);
        lpSeconds += seconds(lpStart);
        ++pairs;

        // Contact at all: the swept hull over the whole step.
        const double sweepGap = separatingAxisGap(sweptHull(moving, v), fixed);
        if (std::fabs(sweepGap) <= 1e3 * tolerance)
        {
            ++ambiguous;  // grazing: either answer is right
            continue;
        }
        ASSERT_EQ(toc.contact, sweepGap < 0.0) << "pair " << i << ", swept-hull gap " << sweepGap;
        if (fullGrid)
        {
            ++gridPairs;
            int first = -1;
            for (int g = 0; g <= gridSteps && first < 0; ++g)
                if (intersectConvexPieces(translated(moving, g * step * v), fixed).intersecting)
                    first = g;
            if (first >= 0)
            {
                ASSERT_TRUE(toc.contact) << "pair " << i << ": the static test finds contact at " << first * step;
                EXPECT_LE(toc.time, first * step + 1e-9) << "pair " << i;
                if (first > 0)
                {
                    EXPECT_GE(toc.time, (first - 1) * step - 1e-9) << "pair " << i;
                }
            }
            else
                ++gridMisses;
        }
        if (!toc.contact)
            continue;
        ++contacts;
        expectWitness(toc, moving, v, fixed);
        EXPECT_TRUE(intersectConvexPieces(translated(moving, toc.time * v), fixed).intersecting) << "pair " << i;
        // The last grid time before the LP's, and no contact up to it.
        const int k = int(std::floor((toc.time - 1e-9) / step));
        if (k >= 0 && k * step < toc.time - 1e-9)
        {
            const ConvexPiece before = sweptHull(moving, k * step * v);
            EXPECT_FALSE(intersectConvexPieces(before, fixed).intersecting)
                << "pair " << i << ": contact before grid time " << k * step << ", LP time " << toc.time;
        }
    }
    std::printf("[random hulls vs static narrow phase] %d pairs (%d on the full 1e-4 grid, %d of them without "
                "contact), %d contacts, %d grazing (skipped); LP %.2f us/pair; %.2f s in all\n",
                pairs, gridPairs, gridMisses, contacts, ambiguous, 1e6 * lpSeconds / pairs, seconds(start));
    EXPECT_GT(contacts, pairs / 4);
    EXPECT_LT(contacts, pairs * 9 / 10);
    EXPECT_LT(ambiguous, pairs / 50);
}

// ---------------------------------------------------------------------------------------------
// Penetration depth.

std::vector<Vec3> fibonacciSphere(int n)
{
    std::vector<Vec3> directions;
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i)
    {
        const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), phi = golden * i;
        directions.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
    return directions;
}

// h(n) = max_B n . b - min_A n . a: how far A must move along +n to clear B.
double supportDepth(const ConvexPiece &a, const ConvexPiece &b, const Vec3 &n)
{
    double maxB = -kInfinity, minA = kInfinity;
    for (const Vec3 &v : b.vertices)
        maxB = std::max(maxB, n.dot(v));
    for (const Vec3 &v : a.vertices)
        minA = std::min(minA, n.dot(v));
    return maxB - minA;
}

// The exact candidates, computed here independently: face normals and edge-pair crosses.
double exactCandidateMinimum(const ConvexPiece &a, const ConvexPiece &b)
{
    double best = kInfinity;
    const auto consider = [&](const Vec3 &u) {
        if (u.norm() > 0.0)
            best = std::min({best, supportDepth(a, b, u.normalized()), supportDepth(a, b, -u.normalized())});
    };
    for (const Vec3 &n : a.normals)
        consider(n);
    for (const Vec3 &n : b.normals)
        consider(n);
    for (const auto &ea : a.edges)
        for (const auto &eb : b.edges)
            consider((a.vertices[ea[1]] - a.vertices[ea[0]]).cross(b.vertices[eb[1]] - b.vertices[eb[0]]));
    return best;
}

TEST(Penetration, RandomPairsAgainstBruteForce)
{
    TestRandom rng(504);
    std::uniform_int_distribution<int> count(4, 20);
    const std::vector<Vec3> sphere = fibonacciSphere(20000);
    int pairs = 0, disjoint = 0;
    double worstBruteExcess = 0.0, pdSeconds = 0.0, worstDirectional = 0.0;
    const auto start = std::chrono::steady_clock::now();
    while (pairs < 1500)
    {
        const double scale = pairs % 3 == 0 ? 1.0 : (pairs % 3 == 1 ? 1e3 : 1e-3);
        const ConvexPiece a = ConvexPiece::hullOf(randomCloud(rng, count(rng), scale))
                                  .transformed({test::randomRotation(rng), scale * 0.5 * randomInBall(rng)});
        const ConvexPiece b = ConvexPiece::hullOf(randomCloud(rng, count(rng), scale))
                                  .transformed({test::randomRotation(rng), scale * 1.2 * randomInBall(rng)});
        const double magnitude = pairMagnitude(a, b);
        const auto pdStart = std::chrono::steady_clock::now();
        const Penetration pd = penetrationDepth(a, b);
        pdSeconds += seconds(pdStart);
        const double gap = separatingAxisGap(a, b);
        if (!pd.intersecting)
        {
            ++disjoint;
            EXPECT_GT(gap, 0.0);
            EXPECT_EQ(pd.depth, 0.0);
            continue;
        }
        if (gap > -1e-6 * magnitude)
            continue;  // touching or nearly so: the checks below need a clear overlap
        ++pairs;
        EXPECT_NEAR(pd.direction.norm(), 1.0, 1e-12);
        EXPECT_NEAR(pd.depth, -gap, 1e-12 * magnitude);  // the same quantity as the SAT's overlap

        // No direction of the dense sphere, nor any exact candidate, does better.
        double brute = exactCandidateMinimum(a, b);
        EXPECT_NEAR(brute, pd.depth, 1e-12 * magnitude);
        for (const Vec3 &n : sphere)
            brute = std::min(brute, supportDepth(a, b, n));
        worstBruteExcess = std::max(worstBruteExcess, (pd.depth - brute) / magnitude);
        EXPECT_LE(pd.depth, brute + 1e-9 * magnitude) << "pair " << pairs;

        // Moving A by a little more than the depth separates; by a little less does not.
        EXPECT_FALSE(intersectConvexPieces(translated(a, (pd.depth + 1e-7 * magnitude) * pd.direction), b).intersecting)
            << "pair " << pairs;
        EXPECT_TRUE(intersectConvexPieces(translated(a, (pd.depth - 1e-6 * magnitude) * pd.direction), b).intersecting)
            << "pair " << pairs;

        // The directional depth (LP) agrees along the penetration direction and is never less in
        // any other direction.
        const double along = directionalPenetration(a, -pd.direction, b);
        worstDirectional = std::max(worstDirectional, std::fabs(along - pd.depth) / magnitude);
        EXPECT_NEAR(along, pd.depth, 1e-9 * magnitude) << "pair " << pairs;
        const Vec3 u = randomUnit(rng);
        EXPECT_GE(directionalPenetration(a, u, b), pd.depth - 1e-9 * magnitude);
    }
    std::printf("[penetration vs brute force] %d intersecting pairs (%d disjoint drawn); depth - brute-force "
                "minimum at most %.3g relative; directional LP along the PD direction within %.3g relative; "
                "penetrationDepth %.1f us/pair; %.2f s in all\n",
                pairs, disjoint, worstBruteExcess, worstDirectional, 1e6 * pdSeconds / pairs, seconds(start));
}

TEST(Penetration, BoxesAgainstAnalyticAnswer)
{
    TestRandom rng(505);
    int intersecting = 0, matchingDirection = 0;
    for (int i = 0; i < 1000; ++i)
    {
        const Vec3 loA(uniform(rng, -1, 0), uniform(rng, -1, 0), uniform(rng, -1, 0));
        const Vec3 hiA = loA + Vec3(uniform(rng, 0.2, 2), uniform(rng, 0.2, 2), uniform(rng, 0.2, 2));
        const Vec3 loB = Vec3(uniform(rng, -1.5, 0.5), uniform(rng, -1.5, 0.5), uniform(rng, -1.5, 0.5));
        const Vec3 hiB = loB + Vec3(uniform(rng, 0.2, 2), uniform(rng, 0.2, 2), uniform(rng, 0.2, 2));
        // Boxes sharing a frame: the Minkowski difference is a box, the depth its nearest face.
        double expected = kInfinity;
        Vec3 expectedDirection = Vec3::Zero();
        for (int k = 0; k < 3; ++k)
        {
            if (hiB[k] - loA[k] < expected)
                expected = hiB[k] - loA[k], expectedDirection = Vec3::Unit(k);
            if (hiA[k] - loB[k] < expected)
                expected = hiA[k] - loB[k], expectedDirection = -Vec3::Unit(k);
        }
        const RigidTransform pose{test::randomRotation(rng), 2.0 * randomInBall(rng)};
        const ConvexPiece a = ConvexPiece::hullOf(mapped(boxCorners(loA, hiA), pose));
        const ConvexPiece b = ConvexPiece::hullOf(mapped(boxCorners(loB, hiB), pose));
        const Penetration pd = penetrationDepth(a, b);
        if (std::fabs(expected) < 1e-9)
            continue;
        ASSERT_EQ(pd.intersecting, expected > 0.0) << "case " << i;
        if (expected < 0.0)
            continue;
        ++intersecting;
        EXPECT_NEAR(pd.depth, expected, 1e-12) << "case " << i;
        // The direction achieves the depth (it is the analytic one unless two faces tie).
        EXPECT_NEAR(supportDepth(a, b, pd.direction), expected, 1e-12) << "case " << i;
        matchingDirection += (pd.direction - pose.rotation * expectedDirection).norm() < 1e-9;
    }
    std::printf("[penetration, boxes] %d intersecting of 1000, %d with the analytic direction\n", intersecting,
                matchingDirection);
    EXPECT_GT(intersecting, 300);
    EXPECT_GT(matchingDirection, intersecting * 95 / 100);

    // Degenerate pieces: a flat square pushed into a box, a point inside one.
    const ConvexPiece unit = ConvexPiece::hullOf(boxCorners(Vec3(0, 0, 0), Vec3(1, 1, 1)));
    const ConvexPiece square = ConvexPiece::hullOf(
        {Vec3(0.25, 0.25, 0.75), Vec3(0.75, 0.25, 0.75), Vec3(0.75, 0.75, 0.75), Vec3(0.25, 0.75, 0.75)});
    Penetration pd = penetrationDepth(square, unit);
    ASSERT_TRUE(pd.intersecting);
    EXPECT_NEAR(pd.depth, 0.25, 1e-12);
    EXPECT_NEAR((pd.direction - Vec3(0, 0, 1)).norm(), 0.0, 1e-12);
    pd = penetrationDepth(ConvexPiece::hullOf({Vec3(0.5, 0.125, 0.5)}), unit);
    ASSERT_TRUE(pd.intersecting);
    EXPECT_NEAR(pd.depth, 0.125, 1e-12);
    EXPECT_NEAR((pd.direction - Vec3(0, -1, 0)).norm(), 0.0, 1e-12);
    // Disjoint and touching.
    pd = penetrationDepth(ConvexPiece::hullOf(boxCorners(Vec3(2, 0, 0), Vec3(3, 1, 1))), unit);
    EXPECT_FALSE(pd.intersecting);
    EXPECT_EQ(pd.depth, 0.0);
    pd = penetrationDepth(ConvexPiece::hullOf(boxCorners(Vec3(1, 0, 0), Vec3(3, 1, 1))), unit);
    EXPECT_TRUE(pd.intersecting);
    EXPECT_EQ(pd.depth, 0.0);
}

TEST(DirectionalPenetration, BoxesAgainstAnalyticAnswer)
{
    TestRandom rng(506);
    int intersecting = 0;
    double worst = 0.0;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < 2000; ++i)
    {
        const double scale = i % 2 == 0 ? 1.0 : 1e3;
        const Vec3 loA = scale * Vec3(uniform(rng, -1, 0), uniform(rng, -1, 0), uniform(rng, -1, 0));
        const Vec3 hiA = loA + scale * Vec3(uniform(rng, 0.2, 2), uniform(rng, 0.2, 2), uniform(rng, 0.2, 2));
        const Vec3 loB = scale * Vec3(uniform(rng, -1.5, 0.5), uniform(rng, -1.5, 0.5), uniform(rng, -1.5, 0.5));
        const Vec3 hiB = loB + scale * Vec3(uniform(rng, 0.2, 2), uniform(rng, 0.2, 2), uniform(rng, 0.2, 2));
        const Vec3 m = randomUnit(rng);
        // Largest s with A - s m meeting B: per axis, loA - s m <= hiB and hiA - s m >= loB.
        double expected = kInfinity, overlap = kInfinity;
        for (int k = 0; k < 3; ++k)
        {
            overlap = std::min({overlap, hiA[k] - loB[k], hiB[k] - loA[k]});
            if (m[k] > 0.0)
                expected = std::min(expected, (hiA[k] - loB[k]) / m[k]);
            else if (m[k] < 0.0)
                expected = std::min(expected, (loA[k] - hiB[k]) / m[k]);
        }
        const RigidTransform pose{test::randomRotation(rng), scale * 2.0 * randomInBall(rng)};
        const ConvexPiece a = ConvexPiece::hullOf(mapped(boxCorners(loA, hiA), pose));
        const ConvexPiece b = ConvexPiece::hullOf(mapped(boxCorners(loB, hiB), pose));
        const double motionLength = uniform(rng, 0.01, 100.0);
        const double s = directionalPenetration(a, motionLength * (pose.rotation * m), b);
        if (std::fabs(overlap) < 1e-9 * scale)
            continue;
        if (overlap < 0.0)
        {
            EXPECT_EQ(s, 0.0) << "case " << i;
            continue;
        }
        ++intersecting;
        worst = std::max(worst, std::fabs(s - expected) / scale);
        EXPECT_NEAR(s, expected, 1e-9 * scale) << "case " << i;
    }
    std::printf("[directional penetration, boxes] %d intersecting of 2000, worst error %.3g relative; %.1f us/case "
                "including hulls\n",
                intersecting, worst, 1e6 * seconds(start) / 2000);
    EXPECT_GT(intersecting, 600);

    const ConvexPiece unit = ConvexPiece::hullOf(boxCorners(Vec3(0, 0, 0), Vec3(1, 1, 1)));
    EXPECT_THROW(directionalPenetration(unit, Vec3::Zero(), unit), std::invalid_argument);
    // A unit box fully overlapping itself: moving back along any axis takes its full width.
    EXPECT_NEAR(directionalPenetration(unit, Vec3(0, 0, 5), unit), 1.0, 1e-12);
    EXPECT_NEAR(directionalPenetration(unit, Vec3(1, 1, 0), unit), std::sqrt(2.0), 1e-12);
    // Overlapping by 2^-26 of the size, touching, and 2^-26 apart (dyadic: exact).
    const double sliver = std::ldexp(1.0, -26);
    const ConvexPiece right = ConvexPiece::hullOf(boxCorners(Vec3(1 - sliver, 0.25, 0.25), Vec3(2, 0.75, 0.75)));
    EXPECT_NEAR(directionalPenetration(right, Vec3(-1, 0, 0), unit), sliver, 1e-15);
    EXPECT_NEAR(directionalPenetration(right, Vec3(-1, 0.5, 0), unit), sliver * std::sqrt(1.25), 1e-15);
    EXPECT_NEAR(directionalPenetration(translated(right, Vec3(sliver, 0, 0)), Vec3(-1, 0, 0), unit), 0.0, 1e-15);
    EXPECT_EQ(directionalPenetration(translated(right, Vec3(2 * sliver, 0, 0)), Vec3(-1, 0, 0), unit), 0.0);
    // Moving back along the motion would make a disjoint pair overlap: still 0 (they do not meet now).
    EXPECT_EQ(directionalPenetration(translated(right, Vec3(2 * sliver, 0, 0)), Vec3(1, 0, 0), unit), 0.0);
    // A flat square inside the box, having come down: back up by 1/4 to its top face.
    const ConvexPiece square = ConvexPiece::hullOf(
        {Vec3(0.25, 0.25, 0.75), Vec3(0.75, 0.25, 0.75), Vec3(0.75, 0.75, 0.75), Vec3(0.25, 0.75, 0.75)});
    EXPECT_NEAR(directionalPenetration(square, Vec3(0, 0, -1), unit), 0.25, 1e-12);
}
}  // namespace
}  // namespace hcd
