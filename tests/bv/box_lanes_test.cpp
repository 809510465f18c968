// SPDX-License-Identifier: BSD-3-Clause
// The SIMD tests of one box against four (ObbLanes, AabbLanes) against the scalar sphere and
// box tests lane by lane: the same answer on random boxes of every shape and scale, and overlap on
// boxes that touch, nest or coincide.
#include "support/test_support.h"

#include "hybridcd/bv/box_lanes.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>

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

// A box of one of four shapes (solid, flat, needle, a point) at an offset, turned at random.
Obb randomBox(test::TestRandom &rng, double scale)
{
    Obb b;
    b.center = scale * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    b.axes = test::randomRotation(rng);
    const int shape = int(rng() % 4);
    const Vec3 size(uniform(rng, 0.05, 1), uniform(rng, 0.05, 1), uniform(rng, 0.05, 1));
    b.halfExtents = scale * (shape == 0   ? size
                             : shape == 1 ? Vec3(size.x(), size.y(), 0.0)
                             : shape == 2 ? Vec3(size.x(), 0.0, 0.0)
                                          : Vec3::Zero());
    return b;
}

Obb axisBox(const Vec3 &center, const Vec3 &halfExtents, const Mat3 &axes = Mat3::Identity())
{
    Obb b;
    b.center = center;
    b.axes = axes;
    b.halfExtents = halfExtents;
    return b;
}

Mat3 turnAboutZ(double angle)
{
    Mat3 r;
    r << std::cos(angle), -std::sin(angle), 0, std::sin(angle), std::cos(angle), 0, 0, 0, 1;
    return r;
}

// randomBox's centre and extents, along the world axes.
Aabb randomAabb(test::TestRandom &rng, double scale)
{
    const Obb b = randomBox(rng, scale);
    Aabb a;
    a.center = b.center;
    a.halfExtents = b.halfExtents;
    return a;
}

Aabb aabb(const Vec3 &center, const Vec3 &halfExtents)
{
    Aabb a;
    a.center = center;
    a.halfExtents = halfExtents;
    return a;
}

// One to four random boxes from `randomOf` (rng, scale) in lanes, each with a sphere radius from
// `radiusLow` to 1.2 times its circumscribed radius.
template <class Lanes, class RandomBox>
Lanes randomLanes(test::TestRandom &rng, RandomBox randomOf, double scale, double radiusLow)
{
    Lanes lanes;
    const int count = 1 + int(rng() % Lanes::kLanes);
    for (int k = 0; k < count; ++k)
    {
        const auto b = randomOf(rng, scale);
        lanes.add(b, b.halfExtents.norm() * uniform(rng, radiusLow, 1.2), std::uint32_t(k));
    }
    lanes.fill();
    return lanes;
}

// Random boxes from `randomOf` (rng, scale) in 1-4 lanes against another, at scales 1e-6 to 1e6
// and tolerances from 0 to a fifth of the scale, with sphere radii from a fifth of the box's
// circumscribed radius up (so that the sphere test decides some lanes): the kernel's bits equal
// the reference's, and both answers are common (so a kernel that always gave one of them would
// fail). Run once for every instruction set the library was compiled for and this machine has
// (Highway's emulated 128-bit path always among them), each forced in turn.
template <class Lanes, class RandomBox>
void expectAgreementOnRandomBoxesWithTheChosenTarget(std::uint64_t seed, RandomBox randomOf)
{
    test::TestRandom rng(test::seeded(seed));
    int overlapping = 0, separated = 0;
    for (const double scale : {1e-6, 1.0, 1e6})
        for (int trial = 0; trial < 4000; ++trial)
        {
            const auto a = randomOf(rng, scale);
            const Lanes lanes = randomLanes<Lanes>(rng, randomOf, scale, 0.2);
            const int count = lanes.count;
            const double tolerance = trial % 3 == 0 ? 0.0 : uniform(rng, 0.0, 0.2) * scale;
            const double radius = a.halfExtents.norm() * uniform(rng, 0.2, 1.2);
            const unsigned simd = lanesOverlap(lanes, a, radius, tolerance);
            ASSERT_EQ(simd, lanesOverlapReference(lanes, a, radius, tolerance))
                << "scale " << scale << ", trial " << trial;
            ASSERT_EQ(simd >> count, 0u) << "a lane past count answered";
            for (int k = 0; k < count; ++k)
                ((simd >> k) & 1u ? overlapping : separated) += 1;
        }
    EXPECT_GT(overlapping, 2000);
    EXPECT_GT(separated, 2000);
}

// Runs `check` once per instruction set compiled in and present, each forced in turn.
template <class Check>
void forEachTarget(Check check)
{
    for (const std::int64_t target : hwy::SupportedAndGeneratedTargets())
    {
        SCOPED_TRACE(hwy::TargetName(target));
        hwy::SetSupportedTargetsForTest(target);
        check();
        hwy::SetSupportedTargetsForTest(0);
        if (::testing::Test::HasFatalFailure())
            return;
    }
}

template <class Lanes, class RandomBox>
void expectAgreementOnRandomBoxes(std::uint64_t seed, RandomBox randomOf)
{
    forEachTarget([&] { expectAgreementOnRandomBoxesWithTheChosenTarget<Lanes>(seed, randomOf); });
}
// The corners of a box (eight; fewer distinct ones when flat).
std::vector<Vec3> cornersOf(const Obb &b)
{
    std::vector<Vec3> corners;
    for (int k = 0; k < 8; ++k)
        corners.push_back(b.center + b.axes * Vec3((k & 1 ? 1 : -1) * b.halfExtents.x(),
                                                   (k & 2 ? 1 : -1) * b.halfExtents.y(),
                                                   (k & 4 ? 1 : -1) * b.halfExtents.z()));
    return corners;
}
std::vector<Vec3> cornersOf(const Aabb &b) { return cornersOf(axisBox(b.center, b.halfExtents)); }

// As expectAgreementOnRandomBoxes for the distance bounds: the kernel's numbers equal the
// reference's bit for bit, both zero and positive bounds are common, and no bound exceeds the
// distance between two corners of the boxes (points of both, so an independent upper bound on
// their distance).
template <class Lanes, class RandomBox>
void expectEqualBoundsOnRandomBoxesWithTheChosenTarget(std::uint64_t seed, RandomBox randomOf)
{
    test::TestRandom rng(test::seeded(seed));
    int zero = 0, positive = 0;
    for (const double scale : {1e-6, 1.0, 1e6})
        for (int trial = 0; trial < 4000; ++trial)
        {
            const auto a = randomOf(rng, scale);
            const Lanes lanes = randomLanes<Lanes>(rng, randomOf, scale, 1.0);
            const int count = lanes.count;
            const double tolerance = trial % 3 == 0 ? 0.0 : uniform(rng, 0.0, 0.05) * scale;
            const double radius = a.halfExtents.norm() * uniform(rng, 1.0, 1.2);
            double simd[Lanes::kLanes], reference[Lanes::kLanes];
            lanesDistanceLowerBound(lanes, a, radius, tolerance, simd);
            lanesDistanceLowerBoundReference(lanes, a, radius, tolerance, reference);
            for (int k = 0; k < count; ++k)
            {
                ASSERT_EQ(simd[k], reference[k]) << "scale " << scale << ", trial " << trial << ", lane " << k;
                double nearestCorners = std::numeric_limits<double>::infinity();
                for (const Vec3 &p : cornersOf(a))
                    for (const Vec3 &q : cornersOf(lanes.box(k)))
                        nearestCorners = std::min(nearestCorners, (p - q).norm());
                ASSERT_LE(simd[k], nearestCorners * (1.0 + 1e-12)) << "scale " << scale << ", trial " << trial;
                (simd[k] > 0.0 ? positive : zero) += 1;
            }
        }
    EXPECT_GT(zero, 2000);
    EXPECT_GT(positive, 2000);
}

template <class Lanes, class RandomBox>
void expectEqualBoundsOnRandomBoxes(std::uint64_t seed, RandomBox randomOf)
{
    forEachTarget([&] { expectEqualBoundsOnRandomBoxesWithTheChosenTarget<Lanes>(seed, randomOf); });
}
}  // namespace

TEST(ObbLanes, DistanceBoundsEqualTheScalarBoundsOnRandomBoxes)
{
    expectEqualBoundsOnRandomBoxes<ObbLanes>(45, randomBox);
}

TEST(AabbLanes, DistanceBoundsEqualTheScalarBoundsOnRandomBoxes)
{
    expectEqualBoundsOnRandomBoxes<AabbLanes>(47, randomAabb);
}

TEST(ObbLanes, DistanceBoundsOfBoxesApartAlongAFaceOrAnEdge)
{
    for (const double scale : {1e-6, 1.0, 1e6})
    {
        const Obb a = axisBox(Vec3::Zero(), scale * Vec3(1, 1, 1));
        const double r = scale * std::sqrt(3.0);
        ObbLanes lanes;
        lanes.add(axisBox(scale * Vec3(2.5, 0.5, 0), scale * Vec3(1, 1, 1)), r, 0);  // faces 0.5 apart
        // Turned 45 degrees about z: its edge 0.25 from a's face x = 1.
        lanes.add(axisBox(scale * Vec3(1.25 + std::sqrt(2.0), 0, 0), scale * Vec3(1, 1, 1), turnAboutZ(M_PI / 4)), r,
                  1);
        lanes.add(a, r, 2);                                                      // the same box
        lanes.add(axisBox(scale * Vec3(0, 0, 3), scale * Vec3(1, 1, 1)), r, 3);  // faces 1 apart
        lanes.fill();
        double bound[ObbLanes::kLanes];
        lanesDistanceLowerBound(lanes, a, r, 0.0, bound);
        EXPECT_NEAR(bound[0], 0.5 * scale, 1e-12 * scale);
        EXPECT_NEAR(bound[1], 0.25 * scale, 1e-12 * scale);
        EXPECT_EQ(bound[2], 0.0);
        EXPECT_NEAR(bound[3], 1.0 * scale, 1e-12 * scale);
        // A tolerance comes off every positive bound.
        lanesDistanceLowerBound(lanes, a, r, 0.1 * scale, bound);
        EXPECT_NEAR(bound[0], 0.4 * scale, 1e-12 * scale);
        EXPECT_EQ(bound[2], 0.0);
    }
}

TEST(ObbLanes, AgreesWithTheScalarTestsOnRandomBoxes) { expectAgreementOnRandomBoxes<ObbLanes>(41, randomBox); }

TEST(ObbLanes, BoxesThatTouchNestOrCoincideOverlap)
{
    const Obb a = axisBox(Vec3::Zero(), Vec3(1, 1, 1));
    for (const double scale : {1e-6, 1.0, 1e6})
    {
        const Obb s = axisBox(scale * a.center, scale * a.halfExtents);
        ObbLanes lanes;
        // Face to face at x = 1, edge to edge after a turn of 45 degrees about z, nested, the same
        // box.
        lanes.add(axisBox(scale * Vec3(2, 0.5, 0), scale * Vec3(1, 1, 1)), scale * std::sqrt(3.0), 0);
        lanes.add(axisBox(scale * Vec3(1 + std::sqrt(2.0), 0, 0), scale * Vec3(1, 1, 1), turnAboutZ(M_PI / 4)),
                  scale * std::sqrt(3.0), 1);
        lanes.add(axisBox(scale * Vec3(0.2, -0.1, 0.3), scale * Vec3(0.1, 0.2, 0.05), turnAboutZ(0.7)), scale * 0.3, 2);
        lanes.add(s, scale * std::sqrt(3.0), 3);
        lanes.fill();
        EXPECT_EQ(lanesOverlap(lanes, s, scale * std::sqrt(3.0), 0.0), 0xFu) << "scale " << scale;
        EXPECT_EQ(lanesOverlapReference(lanes, s, scale * std::sqrt(3.0), 0.0), 0xFu) << "scale " << scale;

        // Moved apart by a hundredth of their size along x: only the nested and the same box stay.
        ObbLanes apart;
        apart.add(axisBox(scale * Vec3(2.01, 0.5, 0), scale * Vec3(1, 1, 1)), scale * std::sqrt(3.0), 0);
        apart.add(axisBox(scale * Vec3(1.01 + std::sqrt(2.0), 0, 0), scale * Vec3(1, 1, 1), turnAboutZ(M_PI / 4)),
                  scale * std::sqrt(3.0), 1);
        apart.add(axisBox(scale * Vec3(0.2, -0.1, 0.3), scale * Vec3(0.1, 0.2, 0.05), turnAboutZ(0.7)), scale * 0.3, 2);
        apart.fill();
        EXPECT_EQ(lanesOverlap(apart, s, scale * std::sqrt(3.0), 0.0), 0x4u) << "scale " << scale;
        // Within a tolerance of a fiftieth they touch again.
        EXPECT_EQ(lanesOverlap(apart, s, scale * std::sqrt(3.0), 0.02 * scale), 0x7u) << "scale " << scale;
    }
}

TEST(ObbLanes, FlatBoxesInOnePlaneOverlapWhereTheyMeet)
{
    // Two unit squares in the plane z = 0, one turned: flat boxes (a zero extent) that meet.
    const Obb square = axisBox(Vec3::Zero(), Vec3(1, 1, 0));
    ObbLanes lanes;
    lanes.add(axisBox(Vec3(1.9, 0, 0), Vec3(1, 1, 0), turnAboutZ(0.3)), std::sqrt(2.0), 0);
    lanes.add(axisBox(Vec3(0, 3.5, 0), Vec3(1, 1, 0), turnAboutZ(0.3)), std::sqrt(2.0), 1);
    lanes.add(axisBox(Vec3(0, 0, 1e-3), Vec3(1, 1, 0)), std::sqrt(2.0), 2);
    lanes.fill();
    EXPECT_EQ(lanesOverlap(lanes, square, std::sqrt(2.0), 0.0), 0x1u);
    EXPECT_EQ(lanesOverlap(lanes, square, std::sqrt(2.0), 2e-3), 0x5u);
    EXPECT_EQ(lanesOverlapReference(lanes, square, std::sqrt(2.0), 2e-3), 0x5u);
}

TEST(AabbLanes, AgreesWithTheScalarTestsOnRandomBoxes) { expectAgreementOnRandomBoxes<AabbLanes>(43, randomAabb); }

TEST(AabbLanes, BoxesThatTouchNestOrCoincideOverlap)
{
    for (const double scale : {1e-6, 1.0, 1e6})
    {
        const Aabb a = aabb(Vec3::Zero(), scale * Vec3(1, 1, 1));
        // Rounded outward as a tree's radii are: corner to corner, the spheres touch exactly.
        const double r = scale * std::sqrt(3.0) * (1.0 + 1e-12);
        AabbLanes lanes;
        lanes.add(aabb(scale * Vec3(2, 0.5, 0), scale * Vec3(1, 1, 1)), r, 0);           // face to face at x = 1
        lanes.add(aabb(scale * Vec3(2, 2, 2), scale * Vec3(1, 1, 1)), r, 1);             // corner to corner
        lanes.add(aabb(scale * Vec3(0.2, -0.1, 0.3), scale * Vec3(0.1, 0.2, 0)), r, 2);  // nested, flat
        lanes.add(a, r, 3);                                                              // the same box
        lanes.fill();
        EXPECT_EQ(lanesOverlap(lanes, a, r, 0.0), 0xFu) << "scale " << scale;
        EXPECT_EQ(lanesOverlapReference(lanes, a, r, 0.0), 0xFu) << "scale " << scale;

        AabbLanes apart;
        apart.add(aabb(scale * Vec3(2.01, 0.5, 0), scale * Vec3(1, 1, 1)), r, 0);
        apart.add(aabb(scale * Vec3(2.01, 2.01, 2.01), scale * Vec3(1, 1, 1)), r, 1);
        apart.fill();
        EXPECT_EQ(lanesOverlap(apart, a, r, 0.0), 0x0u) << "scale " << scale;
        EXPECT_EQ(lanesOverlap(apart, a, r, 0.02 * scale), 0x3u) << "scale " << scale;
    }
}
