// SPDX-License-Identifier: BSD-3-Clause
// C-tree volumes: the fit keeps the smaller of sphere and box and holds every point; the mixed
// sphere-box distance matches the distance to the box's 12 triangles (an independent computation),
// and the overlap test is conservative for every pair of kinds.
#include "support/test_support.h"

#include "hybridcd/bv/ctree_volume.h"
#include "hybridcd/geometry/triangle_distance.h"

#include <gtest/gtest.h>

#include <random>

using namespace hcd;

namespace
{
// Distance from p to the solid box: 0 inside, else the nearest of its 12 triangles.
double pointBoxDistance(const Vec3 &p, const Obb &b)
{
    if (b.contains(p))
        return 0.0;
    const TriangleMesh cube = test::boxMesh(-b.halfExtents, b.halfExtents);
    const Vec3 local = b.axes.transpose() * (p - b.center);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < cube.triangleCount(); ++t)
        best = std::min(
            best,
            (closestPointOnTriangle(local, cube.corner(t, 0), cube.corner(t, 1), cube.corner(t, 2)) - local).norm());
    return best;
}

std::vector<Vec3> cloud(test::TestRandom &rng, const Vec3 &centre, bool round)
{
    std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.05, 2.0);
    std::normal_distribution<double> g(0.0, 1.0);
    const Mat3 r = test::randomRotation(rng);
    const Vec3 extents = round ? Vec3::Constant(e(rng)) : Vec3(e(rng), e(rng), e(rng));
    std::vector<Vec3> points(30);
    for (Vec3 &p : points)
    {
        // Round clouds: points on a sphere (a ball bounds them better than a box).
        const Vec3 q = round ? Vec3(g(rng), g(rng), g(rng)).normalized() : Vec3(u(rng), u(rng), u(rng));
        p = centre + r * q.cwiseProduct(extents);
    }
    return points;
}
}  // namespace

TEST(CTreeVolume, FitKeepsTheSmallerAndHoldsEveryPoint)
{
    test::TestRandom rng(test::seeded(4101));
    int spheres = 0, boxes = 0;
    for (int i = 0; i < 400; ++i)
    {
        const auto points = cloud(rng, Vec3::Zero(), i % 2 == 0);
        const CTreeVolume v = CTreeVolume::fit(points);
        EXPECT_EQ(v.volume(), std::min(Sphere::fit(points).volume(), Obb::fit(points).volume()));
        for (const Vec3 &p : points)
            EXPECT_TRUE(v.kind == CTreeVolume::Kind::Sphere ? v.sphere.contains(p) : v.box.contains(p));
        (v.kind == CTreeVolume::Kind::Sphere ? spheres : boxes) += 1;
    }
    // Both kinds are chosen on these clouds (round ones favour spheres, flat ones boxes).
    EXPECT_GT(spheres, 40);
    EXPECT_GT(boxes, 40);
}

TEST(CTreeVolume, SphereBoxDistanceMatchesTheBoxTriangles)
{
    test::TestRandom rng(test::seeded(4102));
    std::uniform_real_distribution<double> u(-4.0, 4.0), r(0.0, 1.5);
    for (int i = 0; i < 2000; ++i)
    {
        const Obb box = Obb::fit(cloud(rng, Vec3::Zero(), false));
        const Sphere s{Vec3(u(rng), u(rng), u(rng)), r(rng)};
        const double expected = std::max(0.0, pointBoxDistance(s.center, box) - s.radius);
        EXPECT_NEAR(sphereBoxDistance(s, box), expected, 1e-9);
    }
}

// Pairs of every kind, many within a hair of touching: a point shared by both volumes means overlap,
// and the lower bound never exceeds the distance between sampled contained points.
TEST(CTreeVolume, OverlapIsConservativeForEveryPairOfKinds)
{
    test::TestRandom rng(test::seeded(4103));
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    std::normal_distribution<double> g(0.0, 1.0);
    std::size_t overlapping = 0, apart = 0;
    for (int i = 0; i < 1500; ++i)
    {
        const CTreeVolume a = CTreeVolume::fit(cloud(rng, Vec3::Zero(), i % 3 == 0));
        const CTreeVolume b = CTreeVolume::fit(cloud(rng, Vec3(u(rng), u(rng), u(rng)), i % 2 == 0));
        const bool overlap = ctreeVolumesOverlap(a, b, 0.0);
        (overlap ? overlapping : apart) += 1;
        const double bound = ctreeDistanceLowerBound(a, b, 0.0);
        // With a sphere the bound is the exact gap (box pairs use the OBB bound, which may be 0).
        const bool withSphere = a.kind == CTreeVolume::Kind::Sphere || b.kind == CTreeVolume::Kind::Sphere;
        if (!overlap && withSphere)
            EXPECT_GT(bound, 0.0);
        // Points of each volume, sampled by rejection from its bounding ball.
        const auto inside = [&](const CTreeVolume &v, Vec3 &p) {
            for (int k = 0; k < 200; ++k)
            {
                p = v.center() + v.boundingRadius() * Vec3(g(rng), g(rng), g(rng)).normalized() *
                                     std::cbrt(std::uniform_real_distribution<double>(0.0, 1.0)(rng));
                if (v.kind == CTreeVolume::Kind::Sphere ? v.sphere.contains(p) : v.box.contains(p))
                    return true;
            }
            return false;
        };
        Vec3 p, q;
        for (int k = 0; k < 20; ++k)
            if (inside(a, p) && inside(b, q))
            {
                EXPECT_LE(bound, (p - q).norm() + 1e-12);
                const bool pInB = b.kind == CTreeVolume::Kind::Sphere ? b.sphere.contains(p) : b.box.contains(p);
                if (pInB)
                    EXPECT_TRUE(overlap) << "a shared point, but reported apart";
            }
    }
    EXPECT_GT(overlapping, 100u);
    EXPECT_GT(apart, 100u);
}
