// SPDX-License-Identifier: BSD-3-Clause
// Ellipsoids: the minimum-volume fit (exact containment, known answers, its certificate, cardinality
// reduction) and the overlap and distance queries against independent references.
#include "support/test_support.h"

#include "hybridcd/bv/ellipsoid.h"
#include "hybridcd/bv/minimum_volume_ellipsoid.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <gtest/gtest.h>
#include <nlopt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

using namespace hcd;

namespace
{
double uniform(test::TestRandom &rng, double lo, double hi)
{
    return std::uniform_real_distribution<double>(lo, hi)(rng);
}

double logUniform(test::TestRandom &rng, double lo, double hi)
{
    return std::exp(uniform(rng, std::log(lo), std::log(hi)));
}

Vec3 gaussian(test::TestRandom &rng)
{
    std::normal_distribution<double> n(0.0, 1.0);
    return {n(rng), n(rng), n(rng)};
}

Vec3 unitVector(test::TestRandom &rng)
{
    Vec3 v = gaussian(rng);
    while (v.norm() < 1e-6)
        v = gaussian(rng);
    return v.normalized();
}

Vec3 sortedDescending(Vec3 v)
{
    std::sort(v.data(), v.data() + 3, [](double x, double y) { return x > y; });
    return v;
}

double relativeShapeError(const Mat3 &fitted, const Mat3 &expected)
{
    return (fitted - expected).norm() / expected.norm();
}

// ---------------------------------------------------------------------------------------------------
// Minimum-volume fit

void expectValidFit(const std::vector<Vec3> &points, const MveeResult &fit, const std::string &label)
{
    const Ellipsoid &e = fit.ellipsoid;
    ASSERT_TRUE(e.center.allFinite()) << label;
    ASSERT_TRUE(e.axes.allFinite() && e.semiAxes.allFinite() && e.shape.allFinite()) << label;
    ASSERT_GT(e.semiAxes.minCoeff(), 0.0) << label;
    EXPECT_LT((e.axes.transpose() * e.axes - Mat3::Identity()).norm(), 1e-12) << label;
    EXPECT_TRUE(std::isfinite(fit.optimalityGap) && fit.optimalityGap >= 0.0) << label;
    EXPECT_GE(fit.inflation, 1.0) << label;
    std::size_t outside = 0;
    for (const Vec3 &p : points)
        outside += e.contains(p, 0.0) ? 0 : 1;
    EXPECT_EQ(outside, 0u) << label << ": points outside the fitted ellipsoid";
}

TEST(MinimumVolumeEllipsoid, EnclosesEveryPointExactlyOnAllKindsOfSets)
{
    test::TestRandom rng(11);
    std::vector<std::pair<std::string, std::vector<Vec3>>> sets;
    for (int n : {1, 2, 3, 4, 5, 7, 20, 200, 2000})
    {
        std::vector<Vec3> cloud;
        const Mat3 stretch = test::randomRotation(rng) * Vec3(3.0, 1.0, 0.2).asDiagonal();
        for (int i = 0; i < n; ++i)
            cloud.push_back(stretch * gaussian(rng));
        sets.emplace_back("cloud" + std::to_string(n), cloud);
    }
    {
        std::vector<Vec3> cube;
        for (int i = 0; i < 500; ++i)
            cube.emplace_back(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
        sets.emplace_back("cube", cube);
    }
    {
        // Nearly flat: widths 1, 1e-4, 1e-8 in a rotated frame.
        std::vector<Vec3> sliver;
        const Mat3 r = test::randomRotation(rng);
        for (int i = 0; i < 300; ++i)
            sliver.push_back(r * Vec3(uniform(rng, -1, 1), 1e-4 * uniform(rng, -1, 1), 1e-8 * uniform(rng, -1, 1)));
        sets.emplace_back("sliver", sliver);
    }
    for (int n : {3, 4, 50, 500})
    {
        std::vector<Vec3> flat, rotatedFlat, circle;
        const Mat3 r = test::randomRotation(rng);
        for (int i = 0; i < n; ++i)
        {
            const Vec3 p(uniform(rng, -2, 2), uniform(rng, -1, 1), 0.0);
            flat.push_back(p);
            rotatedFlat.push_back(r * p + Vec3(0.5, -0.25, 2.0));
            const double angle = 2.0 * M_PI * i / n;
            circle.push_back(r * Vec3(std::cos(angle), std::sin(angle), 0.0));
        }
        sets.emplace_back("flat" + std::to_string(n), flat);
        sets.emplace_back("rotatedFlat" + std::to_string(n), rotatedFlat);
        sets.emplace_back("circle" + std::to_string(n), circle);
    }
    for (int n : {2, 3, 30})
    {
        std::vector<Vec3> line;
        const Vec3 direction = unitVector(rng);
        for (int i = 0; i < n; ++i)
            line.push_back(Vec3(0.1, 0.2, 0.3) + uniform(rng, -3, 3) * direction);
        sets.emplace_back("line" + std::to_string(n), line);
    }
    sets.emplace_back("point", std::vector<Vec3>{Vec3(0.1, -0.7, 0.3)});
    sets.emplace_back("repeatedPoint", std::vector<Vec3>(7, Vec3(0.1, -0.7, 0.3)));
    {
        std::vector<Vec3> repeated;
        for (int copy = 0; copy < 10; ++copy)
            for (const Vec3 &p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)})
                repeated.push_back(p);
        sets.emplace_back("repeatedSimplex", repeated);
    }

    const Vec3 hugeOffset(1e6, -0.7e6, 0.3e6);
    int fitted = 0;
    for (const auto &[name, base] : sets)
        for (const double scale : {1.0, 1e-6})
            for (const Vec3 &offset : {Vec3::Zero().eval(), hugeOffset})
            {
                std::vector<Vec3> points;
                for (const Vec3 &p : base)
                    points.push_back(scale * p + offset);
                const std::string label =
                    name + " scale " + std::to_string(scale) + " offset " + std::to_string(offset.x());
                for (const bool hull : {true, false})
                {
                    MveeOptions options;
                    options.useHullCandidates = hull;
                    expectValidFit(points, fitMinimumVolumeEllipsoid(points, options), label + (hull ? " hull" : ""));
                    ++fitted;
                }
            }
    EXPECT_EQ(fitted, int(sets.size()) * 8);

    // The detected dimension of exact degenerate sets (without an offset that rounds them).
    EXPECT_EQ(fitMinimumVolumeEllipsoid({Vec3(1, 2, 3)}).dimension, 0);
    EXPECT_EQ(fitMinimumVolumeEllipsoid({Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(3, 3, 3)}).dimension, 1);
    EXPECT_EQ(fitMinimumVolumeEllipsoid({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}).dimension, 2);
}

TEST(MinimumVolumeEllipsoid, FlatAndCollinearSetsGiveThinEllipsoids)
{
    // A unit square in z = 0: in-plane the MVEE is the circumscribed circle of radius sqrt(2) (by
    // symmetry), across it a thickness near 1e-9 of the extent.
    const std::vector<Vec3> square{Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
    MveeOptions options;
    options.tolerance = 1e-9;
    const MveeResult fit = fitMinimumVolumeEllipsoid(square, options);
    const Vec3 axes = sortedDescending(fit.ellipsoid.semiAxes);
    EXPECT_NEAR(axes[0], std::sqrt(2.0), 1e-6);
    EXPECT_NEAR(axes[1], std::sqrt(2.0), 1e-6);
    EXPECT_GT(axes[2], 0.0);
    EXPECT_LT(axes[2], 1e-6);
    EXPECT_EQ(fit.dimension, 2);

    // A segment: its half-length along the line.
    const MveeResult segment = fitMinimumVolumeEllipsoid({Vec3(1, 1, 1), Vec3(3, 5, 1), Vec3(2, 3, 1)});
    EXPECT_NEAR(sortedDescending(segment.ellipsoid.semiAxes)[0], 0.5 * std::sqrt(20.0), 1e-9);
    EXPECT_LT(sortedDescending(segment.ellipsoid.semiAxes)[1], 1e-6);
    EXPECT_TRUE(segment.ellipsoid.center.isApprox(Vec3(2, 3, 1), 1e-12));
}

TEST(MinimumVolumeEllipsoid, RecoversAKnownEllipsoidFromPointsOnItsSurface)
{
    test::TestRandom rng(12);
    for (int trial = 0; trial < 3; ++trial)
    {
        const Ellipsoid truth = Ellipsoid::fromAxes(
            Vec3(uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5)), test::randomRotation(rng),
            Vec3(logUniform(rng, 0.3, 3), logUniform(rng, 0.3, 3), logUniform(rng, 0.3, 3)));
        std::vector<Vec3> points;
        for (int i = 0; i < 4000; ++i)
            points.push_back(truth.center + truth.axes * truth.semiAxes.cwiseProduct(unitVector(rng)));
        MveeOptions options;
        options.tolerance = 1e-4;
        options.maxIterations = 100000;
        const MveeResult fit = fitMinimumVolumeEllipsoid(points, options);
        expectValidFit(points, fit, "surface");
        EXPECT_LE(fit.optimalityGap, 1e-4);
        EXPECT_LT(relativeShapeError(fit.ellipsoid.shape, truth.shape), 1e-2) << "trial " << trial;
        EXPECT_LT((fit.ellipsoid.center - truth.center).norm(), 1e-2 * truth.boundingRadius()) << "trial " << trial;
    }
}

TEST(MinimumVolumeEllipsoid, MatchesTheAnalyticAnswerForBoxCornersAndARegularSimplex)
{
    test::TestRandom rng(13);
    MveeOptions options;
    options.tolerance = 1e-10;
    options.maxIterations = 100000;
    for (const bool withInterior : {false, true})
    {
        // Box corners: the circumscribed ellipsoid, semi-axes sqrt(3) times the half-extents.
        const Vec3 half(1.0, 2.0, 0.5);
        const Mat3 r = test::randomRotation(rng);
        const Vec3 c(5, -3, 2);
        std::vector<Vec3> corners;
        for (int i = 0; i < 8; ++i)
            corners.push_back(
                c + r * Vec3(i & 1 ? half.x() : -half.x(), i & 2 ? half.y() : -half.y(), i & 4 ? half.z() : -half.z()));
        if (withInterior)  // interior points must change nothing (and are dropped by the hull)
            for (int i = 0; i < 1000; ++i)
                corners.push_back(
                    c + r * half.cwiseProduct(Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1))));
        const MveeResult box = fitMinimumVolumeEllipsoid(corners, options);
        expectValidFit(corners, box, "box");
        const Ellipsoid expected = Ellipsoid::fromAxes(c, r, std::sqrt(3.0) * half);
        EXPECT_LT(relativeShapeError(box.ellipsoid.shape, expected.shape), 1e-6);
        EXPECT_LT((box.ellipsoid.center - c).norm(), 1e-6);
        EXPECT_TRUE(sortedDescending(box.ellipsoid.semiAxes).isApprox(sortedDescending(expected.semiAxes), 1e-6));
        if (withInterior)
        {
            EXPECT_EQ(box.candidates, 8u);
        }
    }
    {
        // Regular tetrahedron: the circumsphere, radius sqrt(3) * scale about the centroid.
        const double scale = 1.7;
        const Mat3 r = test::randomRotation(rng);
        const Vec3 c(-1, 0.5, 4);
        std::vector<Vec3> simplex;
        for (const Vec3 &v : {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)})
            simplex.push_back(c + scale * (r * v));
        const MveeResult fit = fitMinimumVolumeEllipsoid(simplex, options);
        expectValidFit(simplex, fit, "simplex");
        for (int j = 0; j < 3; ++j)
            EXPECT_NEAR(fit.ellipsoid.semiAxes[j], std::sqrt(3.0) * scale, 1e-6 * scale);
        EXPECT_LT((fit.ellipsoid.center - c).norm(), 1e-6);
    }
}

TEST(MinimumVolumeEllipsoid, IsCertifiedWithinTheStatedTolerance)
{
    test::TestRandom rng(14);
    for (int trial = 0; trial < 4; ++trial)
    {
        std::vector<Vec3> points;
        const Mat3 stretch = test::randomRotation(rng) * Vec3(2.0, 1.0, 0.3).asDiagonal();
        for (int i = 0; i < 400; ++i)
            points.push_back(stretch * (trial % 2
                                            ? gaussian(rng)
                                            : Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1))));
        // The reference: all points, no elimination, a far tighter tolerance.
        MveeOptions reference;
        reference.tolerance = 1e-10;
        reference.maxIterations = 1000000;
        reference.useHullCandidates = false;
        reference.cardinalityReduction = false;
        const MveeResult best = fitMinimumVolumeEllipsoid(points, reference);
        ASSERT_LE(best.optimalityGap, 1e-10);
        for (const double tolerance : {1e-1, 1e-2, 1e-3, 1e-4, 1e-6})
        {
            MveeOptions options;
            options.tolerance = tolerance;
            options.maxIterations = 100000;
            const MveeResult fit = fitMinimumVolumeEllipsoid(points, options);
            expectValidFit(points, fit, "certified");
            EXPECT_LE(fit.optimalityGap, tolerance);
            // The certificate's promise, checked against the reference: vol <= (1 + gap)^(3/2) vol(optimal),
            // and no fit is smaller than the optimum.
            const double ratio = fit.ellipsoid.volume() / best.ellipsoid.volume();
            EXPECT_LE(ratio, std::pow(1.0 + fit.optimalityGap, 1.5) * (1.0 + 1e-9)) << "tolerance " << tolerance;
            EXPECT_GE(ratio, 1.0 / std::pow(1.0 + best.optimalityGap, 1.5) - 1e-9) << "tolerance " << tolerance;
            EXPECT_NEAR(fit.inflation, 1.0 + fit.optimalityGap, 1e-6);
        }
    }
}

TEST(MinimumVolumeEllipsoid, CardinalityReductionGivesTheSameEllipsoidAndRemovesPoints)
{
    test::TestRandom rng(15);
    for (int trial = 0; trial < 2; ++trial)
    {
        std::vector<Vec3> points;
        const Mat3 stretch = test::randomRotation(rng) * Vec3(3.0, 1.0, 0.5).asDiagonal();
        for (int i = 0; i < 3000; ++i)
            points.push_back(Vec3(1, 2, 3) + stretch * gaussian(rng));
        MveeOptions full;
        full.tolerance = 1e-6;
        full.maxIterations = 1000000;
        full.useHullCandidates = false;
        full.cardinalityReduction = false;
        MveeOptions reduced = full;
        reduced.cardinalityReduction = true;
        MveeOptions hullAndReduced = reduced;
        hullAndReduced.useHullCandidates = true;
        const MveeResult a = fitMinimumVolumeEllipsoid(points, full);
        const MveeResult b = fitMinimumVolumeEllipsoid(points, reduced);
        const MveeResult c = fitMinimumVolumeEllipsoid(points, hullAndReduced);
        for (const MveeResult *fit : {&a, &b, &c})
        {
            expectValidFit(points, *fit, "reduction");
            EXPECT_LE(fit->optimalityGap, 1e-6);
        }
        EXPECT_EQ(a.removed, 0u);
        EXPECT_GT(b.removed, 0u);
        EXPECT_LT(c.candidates, points.size());
        EXPECT_LT(relativeShapeError(b.ellipsoid.shape, a.ellipsoid.shape), 1e-3);
        EXPECT_LT(relativeShapeError(c.ellipsoid.shape, a.ellipsoid.shape), 1e-3);
        EXPECT_LT((b.ellipsoid.center - a.ellipsoid.center).norm(), 1e-3 * a.ellipsoid.boundingRadius());
        EXPECT_LT((c.ellipsoid.center - a.ellipsoid.center).norm(), 1e-3 * a.ellipsoid.boundingRadius());
        std::cout << "[ reduction ] " << points.size() << " points: full " << a.iterations << " iterations; reduced "
                  << b.iterations << " iterations, " << b.removed << " removed; hull " << c.candidates
                  << " candidates, " << c.removed << " removed, " << c.iterations << " iterations\n";
    }
    {
        // A large cloud: elimination must do real work, and quickly.
        std::vector<Vec3> points;
        for (int i = 0; i < 50000; ++i)
            points.push_back(Vec3(2.0, 1.0, 0.5).cwiseProduct(gaussian(rng)));
        MveeOptions options;
        options.tolerance = 1e-5;
        options.maxIterations = 100000;
        options.useHullCandidates = false;
        const auto start = std::chrono::steady_clock::now();
        const MveeResult fit = fitMinimumVolumeEllipsoid(points, options);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        expectValidFit(points, fit, "large");
        EXPECT_LE(fit.optimalityGap, 1e-5);
        EXPECT_GT(fit.removed, points.size() / 2);
        options.useHullCandidates = true;
        const MveeResult hull = fitMinimumVolumeEllipsoid(points, options);
        expectValidFit(points, hull, "large hull");
        EXPECT_LT(relativeShapeError(hull.ellipsoid.shape, fit.ellipsoid.shape), 1e-2);
        std::cout << "[ reduction ] " << points.size() << " points without hull: " << fit.removed << " removed, "
                  << fit.iterations << " iterations, " << seconds << " s; with hull: " << hull.candidates
                  << " candidates, " << hull.removed << " removed, " << hull.iterations << " iterations\n";
    }
}

TEST(MinimumVolumeEllipsoid, RejectsEmptyAndNonFiniteInput)
{
    EXPECT_THROW(fitMinimumVolumeEllipsoid({}), std::invalid_argument);
    EXPECT_THROW(fitMinimumVolumeEllipsoid({Vec3(0, 0, 0), Vec3(NAN, 0, 0)}), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------
// Ellipsoid basics

TEST(Ellipsoid, PrincipalAndShapeFormsAgreeAndTransform)
{
    test::TestRandom rng(16);
    for (int trial = 0; trial < 100; ++trial)
    {
        const Ellipsoid e =
            Ellipsoid::fromAxes(gaussian(rng), test::randomRotation(rng),
                                Vec3(logUniform(rng, 0.1, 3), logUniform(rng, 0.1, 3), logUniform(rng, 0.1, 3)));
        const Ellipsoid f = Ellipsoid::fromShape(e.center, e.shape);
        EXPECT_TRUE(sortedDescending(f.semiAxes).isApprox(sortedDescending(e.semiAxes), 1e-12));
        EXPECT_LT((e.inverseShape() * e.shape - Mat3::Identity()).norm(), 1e-10);
        EXPECT_NEAR(e.volume(), 4.0 / 3.0 * M_PI * e.semiAxes.prod(), 1e-12 * e.volume());
        const RigidTransform pose{test::randomRotation(rng), gaussian(rng)};
        const Ellipsoid moved = e.transformed(pose);
        for (int k = 0; k < 20; ++k)
        {
            const Vec3 p = e.center + 2.0 * e.boundingRadius() * gaussian(rng) / 3.0;
            const double before = (p - e.center).dot(e.shape * (p - e.center));
            EXPECT_NEAR(e.normalizedRadiusSquared(p), before, 1e-9 * (1 + before));
            EXPECT_NEAR(moved.normalizedRadiusSquared(pose.apply(p)), before, 1e-9 * (1 + before));
            const Vec3 n = unitVector(rng);
            // The support point c + A^{-1} n / sqrt(n^T A^{-1} n) lies on the surface.
            const Vec3 s = e.center + e.inverseShape() * n / e.supportRadius(n);
            EXPECT_NEAR(e.normalizedRadiusSquared(s), 1.0, 1e-9);
            EXPECT_NEAR(e.support(n), n.dot(s), 1e-9);
        }
    }
}

// ---------------------------------------------------------------------------------------------------
// Overlap: an independent reference

enum class Verdict
{
    Overlap,
    Disjoint,
    Unknown
};

/// Own evaluation of the definition, (x - c)^T A (x - c) with A^{-1/2} = axes diag(semiAxes).
double formValue(const Ellipsoid &e, const Vec3 &x)
{
    const Vec3 local = e.axes.transpose() * (x - e.center);
    return (local.array() / e.semiAxes.array()).square().sum();
}

/// h(n) - n.c = sqrt(n^T A^{-1} n) with A^{-1} assembled here.
double supportReach(const Ellipsoid &e, const Vec3 &n)
{
    const Mat3 inverse = e.axes * e.semiAxes.cwiseAbs2().asDiagonal() * e.axes.transpose();
    return std::sqrt(std::max(0.0, n.dot(inverse * n)));
}

/// A plane with normal n separates a and b when the support of a along n is below that of b along -n.
bool separates(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &n)
{
    return n.dot(a.center) + supportReach(a, n) < n.dot(b.center) - supportReach(b, n);
}

/// The minimum of a's quadratic form over b (a trust-region subproblem, solved through the secular
/// equation): the pair overlaps iff it is <= 1. Also returns the minimiser and a's gradient there, which
/// is the optimal separating normal when the minimum exceeds 1.
struct FormMinimum
{
    double value = 0.0;
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::Zero();
    Vec3 z = Vec3::Zero();
};

FormMinimum minimiseFormOver(const Ellipsoid &a, const Ellipsoid &b)
{
    const Mat3 ra = a.semiAxes.cwiseInverse().asDiagonal() * a.axes.transpose();
    const Mat3 lb = b.axes * b.semiAxes.asDiagonal();
    const Mat3 h = ra * lb;
    const Vec3 g = ra * (b.center - a.center);
    FormMinimum result;
    Vec3 z = -h.fullPivLu().solve(g);
    if (!(z.norm() <= 1.0))
    {
        const Eigen::SelfAdjointEigenSolver<Mat3> solver(h.transpose() * h);
        const Vec3 lambda = solver.eigenvalues().cwiseMax(0.0);
        const Vec3 beta = solver.eigenvectors().transpose() * (h.transpose() * g);
        auto zOf = [&](double mu) {
            return Vec3(-(solver.eigenvectors() * beta.cwiseQuotient((lambda.array() + mu).matrix())));
        };
        double lo = 0.0, hi = beta.norm();
        for (int iteration = 0; iteration < 200 && hi > lo; ++iteration)
        {
            const double mid = 0.5 * (lo + hi);
            if (mid <= lo || mid >= hi)
                break;
            (zOf(mid).norm() > 1.0 ? lo : hi) = mid;
        }
        z = zOf(hi);
        z /= std::max(1.0, z.norm());
    }
    result.z = z;
    result.point = b.center + lb * z;
    const Vec3 residual = g + h * z;
    result.value = residual.squaredNorm();
    result.normal = ra.transpose() * residual;
    return result;
}

/// The Perram–Wertheim normal, found here by a dense grid over l and golden-section refinement.
Vec3 gridContactNormal(const Ellipsoid &a, const Ellipsoid &b)
{
    const Mat3 ai = a.axes * a.semiAxes.cwiseAbs2().asDiagonal() * a.axes.transpose();
    const Mat3 bi = b.axes * b.semiAxes.cwiseAbs2().asDiagonal() * b.axes.transpose();
    const Vec3 d = b.center - a.center;
    auto value = [&](double l) { return l * (1 - l) * d.dot(((1 - l) * ai + l * bi).ldlt().solve(d)); };
    int best = 1;
    for (int i = 1; i < 1000; ++i)
        if (value(i / 1000.0) > value(best / 1000.0))
            best = i;
    double lo = (best - 1) / 1000.0, hi = (best + 1) / 1000.0;
    const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int iteration = 0; iteration < 80; ++iteration)
    {
        const double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
        (value(x1) < value(x2) ? lo : hi) = (value(x1) < value(x2) ? x1 : x2);
    }
    const double l = 0.5 * (lo + hi);
    return ((1 - l) * ai + l * bi).ldlt().solve(d);
}

/// NLopt minimisation of the support gap n.ca + h_a(n) - n.cb + h_b(n) over unit normals; a negative
/// value is a separating plane.
bool searchSeparatingNormal(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &start)
{
    struct Data
    {
        const Ellipsoid *a, *b;
        bool found;
    } data{&a, &b, false};
    nlopt::opt optimiser(nlopt::LN_NELDERMEAD, 3);
    optimiser.set_min_objective(
        [](unsigned, const double *x, double *, void *raw) -> double {
            auto &data = *static_cast<Data *>(raw);
            const Vec3 w(x[0], x[1], x[2]);
            if (!(w.norm() > 0.0))
                return 1e300;
            const Vec3 n = w.normalized();
            if (separates(*data.a, *data.b, n))
                data.found = true;
            return n.dot(data.a->center - data.b->center) + supportReach(*data.a, n) + supportReach(*data.b, n);
        },
        &data);
    optimiser.set_xtol_rel(1e-14);
    optimiser.set_maxeval(3000);
    optimiser.set_stopval(-1e-300);
    std::vector<double> x{start.x(), start.y(), start.z()};
    if (!(start.norm() > 0.0) || !start.allFinite())
        x = {1.0, 0.0, 0.0};
    double value = 0.0;
    try
    {
        optimiser.optimize(x, value);
    }
    catch (const std::exception &)
    {
    }
    return data.found;
}

/// The reference's best relative margin of separation: max over normals n of n.d / (h_a(n) + h_b(n)) - 1,
/// d = cb - ca, i.e. how far both ellipsoids could be scaled about their centres before they touch
/// (negative for overlapping pairs). NLopt's Nelder–Mead from the trust-region and grid normals.
double referenceScalingGap(const Ellipsoid &a, const Ellipsoid &b)
{
    struct Data
    {
        const Ellipsoid *a, *b;
        double best;
    } data{&a, &b, -std::numeric_limits<double>::infinity()};
    auto margin = [](const Ellipsoid &a, const Ellipsoid &b, const Vec3 &w) {
        if (!(w.norm() > 0.0) || !w.allFinite())
            return -std::numeric_limits<double>::infinity();
        const Vec3 n = w.normalized();
        return n.dot(b.center - a.center) / (supportReach(a, n) + supportReach(b, n)) - 1.0;
    };
    const std::vector<Vec3> starts{minimiseFormOver(a, b).normal, -minimiseFormOver(b, a).normal,
                                   gridContactNormal(a, b)};
    for (const Vec3 &start : starts)
    {
        data.best = std::max(data.best, margin(a, b, start));
        if (!(start.norm() > 0.0) || !start.allFinite())
            continue;
        const Vec3 unit = start.normalized();
        nlopt::opt optimiser(nlopt::LN_NELDERMEAD, 3);
        optimiser.set_max_objective(
            [](unsigned, const double *x, double *, void *raw) -> double {
                auto &data = *static_cast<Data *>(raw);
                const Vec3 w(x[0], x[1], x[2]);
                if (!(w.norm() > 0.0))
                    return -1e300;
                const Vec3 n = w.normalized();
                const double value =
                    n.dot(data.b->center - data.a->center) / (supportReach(*data.a, n) + supportReach(*data.b, n)) -
                    1.0;
                data.best = std::max(data.best, value);
                return value;
            },
            &data);
        optimiser.set_xtol_rel(1e-15);
        optimiser.set_maxeval(3000);
        std::vector<double> x{unit.x(), unit.y(), unit.z()};
        double value = 0.0;
        try
        {
            optimiser.optimize(x, value);
        }
        catch (const std::exception &)
        {
        }
    }
    return data.best;
}

bool witnessInBoth(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &x)
{
    return formValue(a, x) <= 1.0 && formValue(b, x) <= 1.0;
}

/// The reference verdict: overlap needs a common point, disjoint a separating plane.
Verdict referenceVerdict(const Ellipsoid &a, const Ellipsoid &b, test::TestRandom &rng)
{
    const FormMinimum ab = minimiseFormOver(a, b), ba = minimiseFormOver(b, a);
    // Witnesses: the minimisers, pulled slightly towards the centre of the ellipsoid they lie in.
    for (const double t : {1.0, 1.0 - 1e-13, 1.0 - 1e-11, 1.0 - 1e-9, 1.0 - 1e-7})
    {
        if (witnessInBoth(a, b, b.center + t * (ab.point - b.center)) ||
            witnessInBoth(a, b, a.center + t * (ba.point - a.center)))
            return Verdict::Overlap;
    }
    if (separates(a, b, ab.normal) || separates(a, b, -ba.normal) || separates(a, b, gridContactNormal(a, b)))
        return Verdict::Disjoint;
    // Dense sampling of the smaller ellipsoid along rays from its centre.
    const Ellipsoid &small = a.volume() < b.volume() ? a : b;
    for (int ray = 0; ray < 200; ++ray)
    {
        const Vec3 u = unitVector(rng);
        for (int step = 0; step <= 16; ++step)
            if (witnessInBoth(a, b, small.center + small.axes * small.semiAxes.cwiseProduct(u) * (step / 16.0)))
                return Verdict::Overlap;
    }
    if (searchSeparatingNormal(a, b, ab.normal))
        return Verdict::Disjoint;
    return Verdict::Unknown;
}

Ellipsoid randomShape(test::TestRandom &rng, const std::string &kind, const Vec3 &center)
{
    const double size = logUniform(rng, 0.3, 2.0);
    Vec3 semi;
    if (kind == "flat")
        semi = Vec3(size, size * uniform(rng, 0.3, 1.0), 1e-3 * size);
    else if (kind == "elongated")
        semi = Vec3(size, 1e-3 * size, 1e-3 * size * uniform(rng, 0.3, 1.0));
    else
        semi = Vec3(logUniform(rng, 0.2, 2.0), logUniform(rng, 0.2, 2.0), logUniform(rng, 0.2, 2.0));
    return Ellipsoid::fromAxes(center, test::randomRotation(rng), semi);
}

Ellipsoid scaledAboutCenter(const Ellipsoid &e, double scale)
{
    return Ellipsoid::fromAxes(e.center, e.axes, e.semiAxes * scale);
}

struct Tally
{
    long pairs = 0, referenceOverlap = 0, referenceDisjoint = 0, unknown = 0;
    long falseDisjoint = 0;        // said disjoint, reference found a common point: must be 0
    long conservativeOverlap = 0;  // said overlap, reference found a separating plane
    long truePositives = 0;        // said disjoint, reference agrees
};

TEST(EllipsoidOverlap, NeverReportsDisjointForOverlappingPairs)
{
    test::TestRandom rng(17);
    const auto start = std::chrono::steady_clock::now();
    std::map<std::string, Tally> tallies;
    double worstConservativeGap = 0.0;  // largest reference scaling gap among pairs said to overlap
    auto check = [&](const std::string &group, const Ellipsoid &a, const Ellipsoid &b) {
        Tally &t = tallies[group];
        ++t.pairs;
        const bool overlap = ellipsoidsOverlap(a, b);
        const Verdict verdict = referenceVerdict(a, b, rng);
        if (verdict == Verdict::Unknown)
        {
            ++t.unknown;
            return;
        }
        if (verdict == Verdict::Overlap)
        {
            ++t.referenceOverlap;
            if (!overlap)
            {
                ++t.falseDisjoint;
                ADD_FAILURE() << group << ": reported disjoint for an overlapping pair\n  a: c=" << a.center.transpose()
                              << " s=" << a.semiAxes.transpose() << "\n  b: c=" << b.center.transpose()
                              << " s=" << b.semiAxes.transpose();
            }
        }
        else
        {
            ++t.referenceDisjoint;
            (overlap ? t.conservativeOverlap : t.truePositives) += 1;
            if (overlap)
            {
                // Allowed only within the certification margin: the pair could be scaled about its
                // centres by at most about 1 + 1e-9 before touching.
                const double gap = referenceScalingGap(a, b);
                worstConservativeGap = std::max(worstConservativeGap, gap);
                EXPECT_LE(gap, 2e-9) << group << ": overlap reported for a pair separated by a relative margin " << gap;
            }
        }
        // The answer must not depend on the order.
        EXPECT_EQ(ellipsoidsOverlap(b, a), overlap) << group;
    };

    const std::vector<std::string> kinds{"generic", "flat", "elongated"};
    // Random placements.
    for (int i = 0; i < 36000; ++i)
    {
        const std::string kindA = kinds[std::size_t(i % 3)], kindB = kinds[std::size_t((i / 3) % 3)];
        const double spread = (kindA == "generic" && kindB == "generic") ? 3.0 : 1.5;
        const Ellipsoid a = randomShape(rng, kindA, Vec3::Zero());
        const Ellipsoid b =
            randomShape(rng, kindB, spread * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)));
        check("random " + kindA + "/" + kindB, a, b);
    }
    // Nested pairs: b inside a, possibly touching a's surface from inside, in both orders.
    for (int i = 0; i < 12000; ++i)
    {
        const Ellipsoid a = randomShape(rng, kinds[std::size_t(i % 3)], gaussian(rng));
        const double shrink = (i % 4 == 0) ? 1.0 - 1e-9 : uniform(rng, 0.05, 0.9);
        const Vec3 offset = a.axes * a.semiAxes.cwiseProduct(unitVector(rng)) * (1.0 - shrink) * uniform(rng, 0.0, 1.0);
        const Ellipsoid b = Ellipsoid::fromAxes(a.center + offset, a.axes, a.semiAxes * shrink);
        const Ellipsoid tiny =
            Ellipsoid::fromAxes(a.center + 0.999 * (a.axes * a.semiAxes.cwiseProduct(unitVector(rng))),
                                test::randomRotation(rng), Vec3::Constant(1e-4 * a.semiAxes.minCoeff()));
        check("nested", i % 2 ? a : b, i % 2 ? b : a);
        check("nested tiny", a, tiny);
    }
    // Thin discs (the shape the fit gives flat point sets: thickness 1e-9 of the extent), nearly
    // coplanar, overlapping in the plane or slightly apart across it.
    for (int i = 0; i < 3000; ++i)
    {
        const Mat3 r = test::randomRotation(rng);
        const Mat3 spin = Eigen::AngleAxisd(uniform(rng, 0, M_PI), Vec3::UnitZ()).toRotationMatrix();
        const Mat3 tilt = Eigen::AngleAxisd(i % 2 ? 1e-7 : 0.0, Vec3::UnitX()).toRotationMatrix();
        const Ellipsoid a = Ellipsoid::fromAxes(Vec3::Zero(), r, Vec3(1.0, 0.7, 1e-9));
        const Vec3 shift = r * Vec3(uniform(rng, -2, 2), uniform(rng, -1.5, 1.5), (i % 3) * uniform(rng, 0.0, 4e-9));
        check("thin discs", a, Ellipsoid::fromAxes(shift, r * tilt * spin, Vec3(0.8, 0.5, 1e-9)));
    }
    // Near-touching: scale b about its centre to the touching scale (bisection on the reference's
    // trust-region minimum), then just below and above it.
    const std::vector<double> offsets{-1e-2, -1e-4, -1e-6, -1e-8, 1e-8, 1e-6, 1e-4, 1e-2};
    for (int i = 0; i < 6000; ++i)
    {
        const std::string kindA = kinds[std::size_t(i % 3)], kindB = kinds[std::size_t((i / 3) % 3)];
        const Ellipsoid a = randomShape(rng, kindA, Vec3::Zero());
        Ellipsoid b = randomShape(rng, kindB, Vec3::Zero());
        b = Ellipsoid::fromAxes((a.boundingRadius() + b.boundingRadius()) * uniform(rng, 0.3, 1.2) * unitVector(rng),
                                b.axes, b.semiAxes);
        if (formValue(a, b.center) <= 1.0 || formValue(b, a.center) <= 1.0)
            continue;
        auto touches = [&](double scale) { return minimiseFormOver(a, scaledAboutCenter(b, scale)).value <= 1.0; };
        double lo = 1.0, hi = 1.0;
        while (touches(lo) && lo > 1e-12)
            lo *= 0.5;
        while (!touches(hi) && hi < 1e12)
            hi *= 2.0;
        for (int iteration = 0; iteration < 64; ++iteration)
        {
            const double mid = 0.5 * (lo + hi);
            (touches(mid) ? hi : lo) = mid;
        }
        for (const double offset : offsets)
            check("touching " + kindA + "/" + kindB + (offset < 0 ? " apart" : " into"), a,
                  scaledAboutCenter(b, hi * (1.0 + offset)));
    }

    Tally all;
    for (const auto &[group, t] : tallies)
    {
        all.pairs += t.pairs;
        all.referenceOverlap += t.referenceOverlap;
        all.referenceDisjoint += t.referenceDisjoint;
        all.unknown += t.unknown;
        all.falseDisjoint += t.falseDisjoint;
        all.conservativeOverlap += t.conservativeOverlap;
        all.truePositives += t.truePositives;
        std::cout << "[ overlap ] " << group << ": " << t.pairs << " pairs, reference " << t.referenceOverlap
                  << " overlap / " << t.referenceDisjoint << " disjoint / " << t.unknown
                  << " undecided; false disjoint " << t.falseDisjoint << ", overlap said for separated pairs "
                  << t.conservativeOverlap << "\n";
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "[ overlap ] total " << all.pairs << " pairs (" << all.referenceOverlap << " overlapping, "
              << all.referenceDisjoint << " separated, " << all.unknown << " undecided and skipped); false disjoint "
              << all.falseDisjoint << "; said overlap for a separated pair " << all.conservativeOverlap << "; "
              << seconds << " s\n";
    std::cout << "[ overlap ] largest relative separation among separated pairs said to overlap: "
              << worstConservativeGap << "\n";
    EXPECT_GE(all.pairs, 100000);
    EXPECT_EQ(all.falseDisjoint, 0);
    EXPECT_LT(double(all.unknown), 0.01 * double(all.pairs));
    // Saying "overlap" for separated pairs is allowed only within the certification margin, which only
    // the 1e-8 near-touching pairs come close to.
    EXPECT_LT(double(all.conservativeOverlap), 0.01 * double(all.referenceDisjoint));
}

// ---------------------------------------------------------------------------------------------------
// Distance

/// An upper bound on the distance: for any unit u the support points c_a + A^{-1} u / h_a(u) of a and
/// c_b - B^{-1} u / h_b(u) of b lie in the ellipsoids, so their distance bounds the true one; NLopt's
/// Nelder–Mead minimises it over u from several starts.
double referenceDistanceUpperBound(const Ellipsoid &a, const Ellipsoid &b, test::TestRandom &rng)
{
    struct Data
    {
        const Ellipsoid *a, *b;
        double best;
    } data{&a, &b, std::numeric_limits<double>::infinity()};
    auto gapOf = [](const Ellipsoid &a, const Ellipsoid &b, const Vec3 &n) {
        const Mat3 ai = a.axes * a.semiAxes.cwiseAbs2().asDiagonal() * a.axes.transpose();
        const Mat3 bi = b.axes * b.semiAxes.cwiseAbs2().asDiagonal() * b.axes.transpose();
        const Vec3 p = a.center + ai * n / supportReach(a, n);
        const Vec3 q = b.center - bi * n / supportReach(b, n);
        return (p - q).norm();
    };
    std::vector<Vec3> starts{(b.center - a.center).normalized(), gridContactNormal(a, b).normalized()};
    for (int k = 0; k < 3; ++k)
        starts.push_back(unitVector(rng));
    for (const Vec3 &start : starts)
    {
        nlopt::opt optimiser(nlopt::LN_NELDERMEAD, 3);
        optimiser.set_min_objective(
            [](unsigned, const double *x, double *, void *raw) -> double {
                auto &data = *static_cast<Data *>(raw);
                const Vec3 w(x[0], x[1], x[2]);
                if (!(w.norm() > 0.0))
                    return 1e300;
                const Mat3 ai = data.a->axes * data.a->semiAxes.cwiseAbs2().asDiagonal() * data.a->axes.transpose();
                const Mat3 bi = data.b->axes * data.b->semiAxes.cwiseAbs2().asDiagonal() * data.b->axes.transpose();
                const Vec3 n = w.normalized();
                const Vec3 p = data.a->center + ai * n / supportReach(*data.a, n);
                const Vec3 q = data.b->center - bi * n / supportReach(*data.b, n);
                const double value = (p - q).norm();
                data.best = std::min(data.best, value);
                return value;
            },
            &data);
        optimiser.set_xtol_rel(1e-15);
        optimiser.set_ftol_rel(1e-16);
        optimiser.set_maxeval(4000);
        std::vector<double> x{start.x(), start.y(), start.z()};
        double value = 0.0;
        try
        {
            optimiser.optimize(x, value);
        }
        catch (const std::exception &)
        {
        }
        data.best = std::min(data.best, gapOf(a, b, start));
    }
    return data.best;
}

TEST(EllipsoidDistance, IsALowerBoundThatMatchesTheReference)
{
    test::TestRandom rng(18);
    // Balls: exact.
    for (int i = 0; i < 100; ++i)
    {
        const Ellipsoid a =
            Ellipsoid::fromAxes(gaussian(rng), test::randomRotation(rng), Vec3::Constant(logUniform(rng, 0.1, 2)));
        const Ellipsoid b = Ellipsoid::fromAxes(a.center + 5.0 * unitVector(rng), test::randomRotation(rng),
                                                Vec3::Constant(logUniform(rng, 0.1, 2)));
        const double expected = (b.center - a.center).norm() - a.semiAxes[0] - b.semiAxes[0];
        const double distance = ellipsoidDistance(a, b);
        EXPECT_LE(distance, expected * (1 + 1e-9));
        EXPECT_NEAR(distance, expected, 1e-9 * expected);
    }
    const std::vector<std::string> kinds{"generic", "flat", "elongated"};
    int separated = 0, overlapping = 0;
    double worstLow = 0.0;
    for (int i = 0; i < 1500; ++i)
    {
        const Ellipsoid a = randomShape(rng, kinds[std::size_t(i % 3)], Vec3::Zero());
        const Ellipsoid b = randomShape(rng, kinds[std::size_t((i / 3) % 3)],
                                        4.0 * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)));
        const double distance = ellipsoidDistance(a, b);
        ASSERT_TRUE(std::isfinite(distance) && distance >= 0.0);
        if (ellipsoidsOverlap(a, b))
        {
            EXPECT_EQ(distance, 0.0);
            ++overlapping;
            continue;
        }
        ++separated;
        const double upper = referenceDistanceUpperBound(a, b, rng);
        EXPECT_LE(distance, upper * (1 + 1e-9)) << "pair " << i;
        EXPECT_GE(distance, upper * (1 - 1e-6)) << "pair " << i;
        worstLow = std::max(worstLow, (upper - distance) / upper);
        EXPECT_EQ(ellipsoidDistance(b, a) > 0.0, true);
    }
    std::cout << "[ distance ] " << separated << " separated pairs, " << overlapping
              << " overlapping; largest shortfall below the reference upper bound " << worstLow << " relative\n";
}
}  // namespace
