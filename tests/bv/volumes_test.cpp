// SPDX-License-Identifier: BSD-3-Clause
// Spheres, axis-aligned boxes (dynamic and fixed) and k-DOPs: each fit holds its points, the fit
// of mapped content holds the mapped points, and the overlap and distance tests are conservative
// against brute references (points sampled densely inside the volumes, exact point-set distances).
#include "support/test_support.h"

#include "hybridcd/bv/principal_axis.h"
#include "hybridcd/bvh/volume_traits.h"

#include <Eigen/Eigenvalues>
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

// A cloud of a few kinds: a blob, a flat patch, a needle, at an offset and scale.
std::vector<Vec3> randomCloud(test::TestRandom &rng, int kind, double scale)
{
    const Vec3 offset = scale * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    const Mat3 r = test::randomRotation(rng);
    const Vec3 stretch = kind == 0 ? Vec3(1, 0.7, 0.5) : kind == 1 ? Vec3(1, 0.8, 0) : Vec3(1, 0.02, 0.02);
    std::vector<Vec3> points(3 + std::size_t(rng() % 40));
    for (Vec3 &p : points)
        p = offset +
            scale * (r * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)).cwiseProduct(stretch));
    return points;
}

RigidTransform randomPose(test::TestRandom &rng, double scale)
{
    return {test::randomRotation(rng),
            scale * Vec3(uniform(rng, -1.5, 1.5), uniform(rng, -1.5, 1.5), uniform(rng, -1.5, 1.5))};
}

double pointSetDistance(const std::vector<Vec3> &a, const std::vector<Vec3> &b)
{
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3 &p : a)
        for (const Vec3 &q : b)
            best = std::min(best, (p - q).norm());
    return best;
}

bool contains(const Sphere &v, const Vec3 &p) { return v.contains(p); }
bool contains(const Ssv &v, const Vec3 &p) { return v.contains(p); }
bool contains(const Aabb &v, const Vec3 &p) { return v.contains(p); }
bool contains(const FixedAabb &v, const Vec3 &p) { return v.contains(p); }
template <int K>
bool contains(const KDop<K> &v, const Vec3 &p)
{
    return v.contains(p);
}

// The axis-aligned box around a volume, for rejection sampling inside it.
void boundsOf(const Sphere &v, Vec3 &lo, Vec3 &hi)
{
    lo = v.center.array() - v.radius, hi = v.center.array() + v.radius;
}
void boundsOf(const Ssv &v, Vec3 &lo, Vec3 &hi)
{
    const Vec3 reach = (v.axes.col(0) * v.halfLength[0]).cwiseAbs() + (v.axes.col(1) * v.halfLength[1]).cwiseAbs();
    lo = v.center - reach - Vec3::Constant(v.radius), hi = v.center + reach + Vec3::Constant(v.radius);
}
void boundsOf(const Aabb &v, Vec3 &lo, Vec3 &hi) { lo = v.center - v.halfExtents, hi = v.center + v.halfExtents; }
void boundsOf(const FixedAabb &v, Vec3 &lo, Vec3 &hi)
{
    lo = v.center.array() - v.halfSide, hi = v.center.array() + v.halfSide;
}
template <int K>
void boundsOf(const KDop<K> &v, Vec3 &lo, Vec3 &hi)
{
    lo = Vec3(v.lo[0], v.lo[1], v.lo[2]), hi = Vec3(v.hi[0], v.hi[1], v.hi[2]);
}

template <class Volume>
void checkVolume()
{
    using Traits = VolumeTraits<Volume>;
    test::TestRandom rng(test::seeded(77));
    int apart = 0, sharing = 0;
    for (int trial = 0; trial < test::cases(1500); ++trial)
    {
        const double scale = std::pow(10.0, double(trial % 7) - 3.0);
        const std::vector<Vec3> a = randomCloud(rng, trial % 3, scale), b = randomCloud(rng, (trial / 3) % 3, scale);
        const RigidTransform pose = randomPose(rng, scale);

        // The fit holds its points; the mapped fit holds the mapped points.
        const Volume va = Traits::fit(a), vb = Traits::fit(b);
        for (const Vec3 &p : a)
            ASSERT_TRUE(contains(va, p)) << Traits::kName << " trial " << trial;
        const Volume placed = Traits::transformed(va, pose);
        std::vector<Vec3> mapped;
        for (const Vec3 &p : a)
        {
            mapped.push_back(pose.apply(p));
            ASSERT_TRUE(contains(placed, mapped.back())) << Traits::kName << " mapped, trial " << trial;
            // The hierarchy's sphere about the volume's centre holds the content too.
            ASSERT_LE((mapped.back() - Traits::center(placed)).norm(), Traits::radius(va)) << Traits::kName;
        }

        // Conservative: a lower bound never above the exact distance of the contents, and
        // "apart" never when the contents come closer than the tolerance.
        const double tolerance = 1e-10 * scale;
        const double exact = pointSetDistance(mapped, b);
        EXPECT_LE(Traits::lowerBound(placed, vb, tolerance), exact) << Traits::kName << " trial " << trial;
        if (exact <= tolerance)
            EXPECT_TRUE(Traits::overlap(placed, vb, tolerance)) << Traits::kName;
        const double delta = exact * 1.000001;
        EXPECT_TRUE(Traits::overlap(placed, vb, tolerance + delta)) << Traits::kName << " within " << delta;

        // Against the volumes themselves: a point sampled inside both means "overlap".
        Vec3 lo, hi;
        boundsOf(placed, lo, hi);
        bool common = false;
        for (int s = 0; s < 400 && !common; ++s)
        {
            const Vec3 p(uniform(rng, lo.x(), hi.x()), uniform(rng, lo.y(), hi.y()), uniform(rng, lo.z(), hi.z()));
            common = contains(placed, p) && contains(vb, p);
        }
        if (common)
            EXPECT_TRUE(Traits::overlap(placed, vb, 0.0)) << Traits::kName << " trial " << trial;
        (Traits::overlap(placed, vb, tolerance) ? sharing : apart) += 1;
    }
    // Both answers occur, or the checks above prove little.
    EXPECT_GT(apart, test::cases(1500) / 10) << Traits::kName;
    EXPECT_GT(sharing, test::cases(1500) / 10) << Traits::kName;
}
}  // namespace

TEST(Volumes, SphereFitAndTests) { checkVolume<Sphere>(); }
TEST(Volumes, AabbFitAndTests) { checkVolume<Aabb>(); }
TEST(Volumes, FixedAabbFitAndTests) { checkVolume<FixedAabb>(); }
TEST(Volumes, Kdop14FitAndTests) { checkVolume<KDop<14>>(); }
TEST(Volumes, Kdop18FitAndTests) { checkVolume<KDop<18>>(); }
TEST(Volumes, Kdop26FitAndTests) { checkVolume<KDop<26>>(); }
TEST(Volumes, SweptSphereFitAndTests) { checkVolume<Ssv>(); }

TEST(Volumes, SphereFitIsNearMinimal)
{
    // Points on a unit sphere (and its centre's antipodal pairs): the smallest ball is the unit ball.
    test::TestRandom rng(test::seeded(3));
    for (int trial = 0; trial < 50; ++trial)
    {
        std::vector<Vec3> points;
        const Vec3 c(uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5));
        for (int i = 0; i < 200; ++i)
        {
            const Vec3 u = test::randomRotation(rng).col(0);
            points.push_back(c + u);
            points.push_back(c - u);
        }
        const Sphere s = Sphere::fit(points);
        EXPECT_LE(s.radius, 1.02) << trial;
        EXPECT_GE(s.radius, 1.0 - 1e-9);
    }
    // Ritter's start alone is known to overshoot on a regular simplex; the refinement must not.
    const std::vector<Vec3> tetra = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
    EXPECT_LE(Sphere::fit(tetra).radius, std::sqrt(3.0) * 1.02);
}

TEST(Volumes, KdopPolytopeIsExact)
{
    // The DOPs of a cube's corners are the cube (volume 8 for [-1, 1]^3, up to the fit margin),
    // an octahedron's 14-DOP is bounded by its 8 faces.
    std::vector<Vec3> cube;
    for (int i = 0; i < 8; ++i)
        cube.push_back(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
    EXPECT_NEAR(KDop<14>::fit(cube).volume(), 8.0, 1e-6);
    EXPECT_NEAR(KDop<18>::fit(cube).volume(), 8.0, 1e-6);
    EXPECT_NEAR(KDop<26>::fit(cube).volume(), 8.0, 1e-6);
    const std::vector<Vec3> octahedron = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                                          Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
    EXPECT_NEAR(KDop<14>::fit(octahedron).volume(), 4.0 / 3.0, 1e-6);
    EXPECT_NEAR(KDop<26>::fit(octahedron).volume(), 4.0 / 3.0, 1e-6);
    EXPECT_NEAR(Aabb::fit(octahedron).volume(), 8.0, 1e-6);
    // Every corner satisfies the slabs, and the faces close up (sum of area vectors is zero).
    test::TestRandom rng(test::seeded(11));
    for (int trial = 0; trial < 100; ++trial)
    {
        const auto d = KDop<26>::fit(randomCloud(rng, trial % 3, 1.0));
        Vec3 lo, hi;
        boundsOf(d, lo, hi);
        const double tol = 1e-9 * (1.0 + hi.cwiseAbs().maxCoeff() + lo.cwiseAbs().maxCoeff());
        Vec3 areaSum = Vec3::Zero();
        for (const auto &face : d.faces())
            for (std::size_t k = 1; k + 1 < face.size(); ++k)
                areaSum += (face[k] - face[0]).cross(face[k + 1] - face[0]);
        EXPECT_LE(areaSum.norm(), 1e-6) << trial;
        for (const Vec3 &v : d.vertices())
        {
            const auto &dirs = kdopDirections<26>();
            for (int i = 0; i < 13; ++i)
            {
                EXPECT_LE(dirs[i].dot(v), d.hi[i] + tol);
                EXPECT_GE(dirs[i].dot(v), d.lo[i] - tol);
            }
        }
    }
}

TEST(Volumes, RotatedKdopHoldsTheExactOneAndIsExactOnSymmetries)
{
    // The transformed 26-DOP of a needle holds the exact 26-DOP of the rotated needle (within
    // rounding) for any rotation.
    std::vector<Vec3> needle;
    for (int i = 0; i <= 10; ++i)
        needle.push_back(double(i) / 10.0 * Vec3(1, 1, 1) + Vec3(0.01, -0.01, 0.0) * (i % 2));
    const KDop<26> d = KDop<26>::fit(needle);
    test::TestRandom rng(test::seeded(5));
    for (int trial = 0; trial < 200; ++trial)
    {
        const RigidTransform pose = randomPose(rng, 1.0);
        const KDop<26> moved = d.transformed(pose);
        std::vector<Vec3> mappedCorners;
        for (const Vec3 &v : d.vertices())
            mappedCorners.push_back(pose.apply(v));
        const KDop<26> exact = KDop<26>::fit(mappedCorners);
        for (int i = 0; i < 13; ++i)
        {
            EXPECT_LE(moved.lo[i], exact.lo[i] + 1e-8);
            EXPECT_GE(moved.hi[i], exact.hi[i] - 1e-8);
        }
    }
    // A quarter turn about z permutes the directions (up to sign): the bound is then exact.
    const Mat3 quarter = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()).toRotationMatrix();
    const RigidTransform turn{quarter, Vec3(0.5, -2.0, 3.0)};
    std::vector<Vec3> turned;
    for (const Vec3 &p : needle)
        turned.push_back(turn.apply(p));
    const KDop<26> moved = d.transformed(turn), exact = KDop<26>::fit(turned);
    for (int i = 0; i < 13; ++i)
    {
        EXPECT_NEAR(moved.lo[i], exact.lo[i], 1e-8) << i;
        EXPECT_NEAR(moved.hi[i], exact.hi[i], 1e-8) << i;
    }
}

// The split axis against a two-pass covariance and Eigen's iterative solver (the reference), on
// clouds with one clearly largest spread, far from the origin and at small and large scales; and
// on a large cloud, where the axis comes from a regular sample.
TEST(PrincipalAxis, MatchesTwoPassCovarianceOnElongatedClouds)
{
    test::TestRandom rng(test::seeded(4242));
    for (double scale : {1e-6, 1.0, 1e6})
        for (std::size_t count : {std::size_t(3), std::size_t(50), std::size_t(20000)})
            for (int trial = 0; trial < 20; ++trial)
            {
                const Mat3 r = test::randomRotation(rng);
                const Vec3 offset =
                    1000.0 * scale * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
                std::vector<Vec3> points(count);
                for (Vec3 &p : points)
                    p = offset + scale * (r * Vec3(uniform(rng, -4, 4), uniform(rng, -1, 1), uniform(rng, -0.5, 0.5)));
                Vec3 mean = Vec3::Zero();
                for (const Vec3 &p : points)
                    mean += p;
                mean /= double(count);
                Mat3 covariance = Mat3::Zero();
                for (const Vec3 &p : points)
                    covariance += (p - mean) * (p - mean).transpose();
                const Eigen::SelfAdjointEigenSolver<Mat3> solver(covariance);
                const Vec3 reference = solver.eigenvectors().col(2).normalized();
                const Vec3 axis = principalAxis(points);
                EXPECT_NEAR(axis.norm(), 1.0, 1e-12);
                // Three points can spread alike in two directions; otherwise the axes agree closely.
                if (count > 3)
                    EXPECT_GT(std::fabs(axis.dot(reference)), 0.99) << "scale " << scale << ", " << count << " points";
                // The axis always follows the cloud's long side more than its short ones.
                if (count > 3)
                    EXPECT_GT(std::fabs(axis.dot(r.col(0))), 0.9) << "scale " << scale << ", " << count << " points";
            }
    EXPECT_EQ(principalAxis({}), Vec3::UnitX());
    EXPECT_NEAR(principalAxis(std::vector<Vec3>(5, Vec3(1, 2, 3))).norm(), 1.0, 1e-12);
}
