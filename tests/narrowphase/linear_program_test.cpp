// SPDX-License-Identifier: BSD-3-Clause
// The LP narrow phase against the separating-axis reference: random hulls at unit, huge and tiny
// scales, exactly touching boxes and tetrahedra (dyadic coordinates), nested pieces, flat,
// collinear and single-point pieces. Every answer's certificate is checked as well: the witness
// against both pieces' inequalities, the separating plane against both pieces' vertices.
#include "hybridcd/narrowphase/convex_piece.h"
#include "hybridcd/narrowphase/linear_program.h"
#include "support/test_support.h"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace hcd
{
namespace
{
using test::TestRandom;

constexpr double kRelative = kNarrowPhaseRelativeTolerance;

// ---------------------------------------------------------------------------------------------
// Point sets and pieces.

Vec3 randomInBall(TestRandom &rng)
{
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (;;)
    {
        const Vec3 p(u(rng), u(rng), u(rng));
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

// count points in the unit ball stretched per axis by [0.2, 1] (random aspect), times `scale`.
std::vector<Vec3> randomCloud(TestRandom &rng, int count, double scale)
{
    std::uniform_real_distribution<double> stretch(0.2, 1.0);
    const Vec3 axes(stretch(rng), stretch(rng), stretch(rng));
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

std::vector<Vec3> shifted(std::vector<Vec3> points, const Vec3 &offset)
{
    for (Vec3 &p : points)
        p += offset;
    return points;
}

std::vector<Vec3> scaled(std::vector<Vec3> points, double s)
{
    for (Vec3 &p : points)
        p *= s;
    return points;
}

RigidTransform randomPose(TestRandom &rng, const Vec3 &translation) { return {test::randomRotation(rng), translation}; }

// ---------------------------------------------------------------------------------------------
// Checking one pair.

struct Tally
{
    long pairs = 0, intersecting = 0;
    long disagreements = 0;  // LP and SAT differ, and the pair is not near touching
    long nearTouching = 0;   // LP and SAT differ within 1e-9 relative of touching
    long primalDisagreements = 0;
    long witnessFailures = 0, planeFailures = 0;
    long byCertificate[4] = {0, 0, 0, 0};
    double lpSeconds = 0.0, satSeconds = 0.0;

    void print(const char *name) const
    {
        std::printf("[%s] pairs %ld, intersecting %ld (%.1f%%), disagreements %ld, near-touching %ld, primal "
                    "disagreements %ld, witness failures %ld, plane failures %ld; certificates: witness %ld, LP dual "
                    "%ld, axis search %ld, conservative %ld; LP %.0f ns/pair, SAT %.0f ns/pair\n",
                    name, pairs, intersecting, pairs ? 100.0 * double(intersecting) / double(pairs) : 0.0,
                    disagreements, nearTouching, primalDisagreements, witnessFailures, planeFailures, byCertificate[0],
                    byCertificate[1], byCertificate[2], byCertificate[3], pairs ? 1e9 * lpSeconds / double(pairs) : 0.0,
                    pairs ? 1e9 * satSeconds / double(pairs) : 0.0);
    }
};

double seconds(std::chrono::steady_clock::time_point since)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

std::string describe(const ConvexPiece &a, const ConvexPiece &b)
{
    char text[200];
    std::snprintf(text, sizeof text, "dims %d/%d, faces %zu/%zu, vertices %zu/%zu, magnitude %.3g", a.dimension,
                  b.dimension, a.normals.size(), b.normals.size(), a.vertices.size(), b.vertices.size(),
                  std::max(a.magnitude(), b.magnitude()));
    return text;
}

// Returns the LP's answer after checking its certificate and comparing it with the SAT test.
bool checkPair(const ConvexPiece &a, const ConvexPiece &b, Tally &tally)
{
    const double tolerance = kRelative * std::max(a.magnitude(), b.magnitude());
    auto start = std::chrono::steady_clock::now();
    const IntersectionResult lp = intersectConvexPieces(a, b);
    tally.lpSeconds += seconds(start);
    start = std::chrono::steady_clock::now();
    const bool sat = convexPiecesIntersectSat(a, b);
    tally.satSeconds += seconds(start);

    ++tally.pairs;
    tally.intersecting += lp.intersecting;
    ++tally.byCertificate[int(lp.certificate)];
    if (lp.intersecting)
    {
        const double violation = std::max(a.maxViolation(lp.witness), b.maxViolation(lp.witness));
        if (!(violation <= tolerance) && tally.witnessFailures++ < 10)
            ADD_FAILURE() << "witness violates an inequality by " << violation << " (tolerance " << tolerance << "), "
                          << describe(a, b);
    }
    else
    {
        bool separates = std::abs(lp.separatingNormal.norm() - 1.0) < 1e-12;
        for (const Vec3 &v : a.vertices)
            separates = separates && lp.separatingNormal.dot(v) <= lp.separatingOffset;
        for (const Vec3 &v : b.vertices)
            separates = separates && lp.separatingNormal.dot(v) >= lp.separatingOffset;
        if (!separates && tally.planeFailures++ < 10)
            ADD_FAILURE() << "separating plane fails on a vertex, " << describe(a, b);
    }
    if (lp.intersecting != sat)
    {
        // Near touching by either measure: the SAT gap (a distance) or the LP depth (how far the
        // best point violates a face plane).
        const double gap = separatingAxisGap(a, b);
        const bool near = std::fabs(gap) <= 2.0 * tolerance || std::fabs(lp.depth) <= 2.0 * tolerance;
        (near ? tally.nearTouching : tally.disagreements) += 1;
        if (near || tally.disagreements <= 10)
            std::printf("  %s: LP %s, SAT %s, SAT gap %.3g, LP depth %.3g, tolerance %.3g, %s\n",
                        near ? "near touching" : "DISAGREEMENT", lp.intersecting ? "intersecting" : "disjoint",
                        sat ? "intersecting" : "disjoint", gap, lp.depth, tolerance, describe(a, b).c_str());
    }
    if (!sat && tally.pairs % 8 == 0)
    {
        // The reference's own certificate: its best axis separates the vertices.
        Vec3 axis;
        const double gap = separatingAxisGap(a, b, &axis);
        bool separates = gap > tolerance;
        double maxA = -std::numeric_limits<double>::infinity(), minB = -maxA;
        for (const Vec3 &v : a.vertices)
            maxA = std::max(maxA, axis.dot(v));
        for (const Vec3 &v : b.vertices)
            minB = std::min(minB, axis.dot(v));
        separates = separates && minB - maxA >= 0.5 * gap;
        EXPECT_TRUE(separates) << "SAT axis gap " << gap << ", " << describe(a, b);
    }
    if (convexPiecesIntersectPrimal(a, b) != lp.intersecting)
    {
        const double gap = separatingAxisGap(a, b);
        if (!(std::fabs(gap) <= 2.0 * tolerance || std::fabs(lp.depth) <= 2.0 * tolerance))
            ++tally.primalDisagreements;
    }
    return lp.intersecting;
}

void expectClean(const Tally &tally)
{
    EXPECT_EQ(tally.disagreements, 0);
    EXPECT_EQ(tally.witnessFailures, 0);
    EXPECT_EQ(tally.planeFailures, 0);
    EXPECT_EQ(tally.byCertificate[int(IntersectionResult::Certificate::Conservative)], 0);
}

// ---------------------------------------------------------------------------------------------
// The small LP solver on its own.

// Brute force: the best vertex of the arrangement of constraints and box (every D-subset).
template <int D>
double bruteForceOptimum(const std::vector<Halfspace<D>> &constraints, const Eigen::Matrix<double, D, 1> &c, double box)
{
    std::vector<Halfspace<D>> all = constraints;
    for (int j = 0; j < D; ++j)
    {
        Halfspace<D> h;
        h.a = Eigen::Matrix<double, D, 1>::Unit(j);
        h.b = box;
        all.push_back(h);
        h.a = -h.a;
        all.push_back(h);
    }
    const int n = int(all.size());
    double best = -std::numeric_limits<double>::infinity();
    std::vector<int> pick(D);
    for (int i = 0; i < D; ++i)
        pick[i] = i;
    for (;;)
    {
        Eigen::Matrix<double, D, D> m;
        Eigen::Matrix<double, D, 1> rhs;
        for (int i = 0; i < D; ++i)
            m.row(i) = all[pick[i]].a.transpose(), rhs[i] = all[pick[i]].b;
        Eigen::FullPivLU<Eigen::Matrix<double, D, D>> lu(m);
        if (lu.isInvertible() && std::fabs(lu.determinant()) > 1e-9)
        {
            const Eigen::Matrix<double, D, 1> x = lu.solve(rhs);
            bool feasible = true;
            for (const Halfspace<D> &h : all)
                feasible = feasible && h.a.dot(x) <= h.b + 1e-9 * h.a.norm();
            if (feasible)
                best = std::max(best, c.dot(x));
        }
        int i = D - 1;
        while (i >= 0 && pick[i] == n - D + i)
            --i;
        if (i < 0)
            break;
        ++pick[i];
        for (int j = i + 1; j < D; ++j)
            pick[j] = pick[j - 1] + 1;
    }
    return best;
}

template <int D>
void compareWithBruteForce(int problems, int constraintsPerProblem, TestRandom &rng)
{
    using V = Eigen::Matrix<double, D, 1>;
    std::normal_distribution<double> normal;
    // Offsets chosen so that a good share of the problems are infeasible in every dimension.
    std::uniform_real_distribution<double> offset(D == 2 ? -0.25 : D == 3 ? -0.4 : -0.5, 1.0);
    int infeasible = 0, feasible = 0;
    for (int p = 0; p < problems; ++p)
    {
        std::vector<Halfspace<D>> constraints;
        for (int i = 0; i < constraintsPerProblem; ++i)
        {
            Halfspace<D> h;
            for (int j = 0; j < D; ++j)
                h.a[j] = normal(rng);
            h.a.normalize();
            h.b = offset(rng);
            constraints.push_back(h);
            if (i % 5 == 4)  // a parallel copy and a coincident one
            {
                constraints.push_back({h.a, h.b + 0.25});
                constraints.push_back(h);
            }
        }
        V c;
        for (int j = 0; j < D; ++j)
            c[j] = normal(rng);
        const double box = 3.0;
        const LpSolution<D> s = solveSmallLp<D>(constraints, c, V::Constant(-box), V::Constant(box), 1e-12);
        const double expected = bruteForceOptimum<D>(constraints, c, box);
        if (!std::isfinite(expected))
        {
            ++infeasible;
            EXPECT_EQ(s.status, LpStatus::Infeasible) << "problem " << p;
            continue;
        }
        ++feasible;
        ASSERT_EQ(s.status, LpStatus::Optimal) << "problem " << p;
        EXPECT_NEAR(c.dot(s.x), expected, 1e-9) << "problem " << p;
        // The ordering hint changes the work, never the optimum.
        const V hint = V::Constant(0.1 * double(p % 7));
        const LpSolution<D> hinted = solveSmallLp<D>(constraints, c, V::Constant(-box), V::Constant(box), 1e-12, &hint);
        ASSERT_EQ(hinted.status, LpStatus::Optimal) << "problem " << p;
        EXPECT_NEAR(c.dot(hinted.x), expected, 1e-9) << "problem " << p;
        for (const Halfspace<D> &h : constraints)
            EXPECT_LE(h.a.dot(s.x), h.b + 1e-9);
        // The basis constraints are tight at the optimum.
        for (int id : s.basis)
        {
            if (id >= 0)
            {
                EXPECT_NEAR(constraints[std::size_t(id)].a.dot(s.x), constraints[std::size_t(id)].b, 1e-9);
            }
        }
    }
    std::printf("[small LP, D = %d] %d problems, %d infeasible\n", D, problems, infeasible);
    EXPECT_GT(feasible, problems / 5);
    EXPECT_GT(infeasible, problems / 20);
}

TEST(SmallLp, MatchesBruteForceVertexEnumeration)
{
    TestRandom rng(11);
    compareWithBruteForce<2>(2000, 12, rng);
    compareWithBruteForce<3>(2000, 10, rng);
    compareWithBruteForce<4>(400, 9, rng);
}

TEST(SmallLp, SimpleCases)
{
    using V2 = Eigen::Vector2d;
    const V2 lo(-10, -10), hi(10, 10);
    std::vector<Halfspace<2>> c = {{V2(1, 0), 1.0}, {V2(0, 1), 2.0}, {V2(1, 1), 2.5}};
    LpSolution<2> s = solveSmallLp<2>(c, V2(1, 1), lo, hi, 1e-12);
    ASSERT_EQ(s.status, LpStatus::Optimal);
    EXPECT_NEAR(s.x.sum(), 2.5, 1e-12);

    // x <= -1 and x >= 1: infeasible; x <= 1 and x >= 1: a single point, feasible.
    c = {{V2(1, 0), -1.0}, {V2(-1, 0), -1.0}};
    EXPECT_EQ(solveSmallLp<2>(c, V2(0, 1), lo, hi, 1e-12).status, LpStatus::Infeasible);
    c = {{V2(1, 0), 1.0}, {V2(-1, 0), -1.0}, {V2(1, 0), 1.0}};
    s = solveSmallLp<2>(c, V2(0, 1), lo, hi, 1e-12);
    ASSERT_EQ(s.status, LpStatus::Optimal);
    EXPECT_NEAR(s.x.x(), 1.0, 1e-12);
    EXPECT_NEAR(s.x.y(), 10.0, 1e-12);

    // A zero row is a constant: 0 <= 1 holds, 0 <= -1 does not.
    c = {{V2(0, 0), 1.0}};
    EXPECT_EQ(solveSmallLp<2>(c, V2(1, 0), lo, hi, 1e-12).status, LpStatus::Optimal);
    c = {{V2(0, 0), -1.0}};
    EXPECT_EQ(solveSmallLp<2>(c, V2(1, 0), lo, hi, 1e-12).status, LpStatus::Infeasible);
}

// ---------------------------------------------------------------------------------------------
// Hulls.

void expectConsistent(const ConvexPiece &piece, const std::vector<Vec3> &points)
{
    ASSERT_EQ(piece.normals.size(), piece.offsets.size());
    ASSERT_FALSE(piece.vertices.empty());
    for (std::size_t i = 0; i < piece.normals.size(); ++i)
    {
        EXPECT_NEAR(piece.normals[i].norm(), 1.0, 1e-12);
        EXPECT_TRUE(std::isfinite(piece.offsets[i]));
    }
    for (const Vec3 &p : points)
        EXPECT_LE(piece.maxViolation(p), 0.0);
    for (const auto &e : piece.edges)
    {
        ASSERT_GE(e[0], 0);
        ASSERT_LT(std::size_t(e[1]), piece.vertices.size());
        EXPECT_NE(e[0], e[1]);
    }
    EXPECT_TRUE(piece.centroid.allFinite());
}

TEST(ConvexPiece, HullsOfRegularAndDegenerateSets)
{
    const std::vector<Vec3> cube = boxCorners(Vec3(0, 0, 0), Vec3(1, 1, 1));
    std::vector<Vec3> withInterior = cube;
    withInterior.emplace_back(0.5, 0.5, 0.5);
    withInterior.emplace_back(0.5, 0.5, 1.0);  // on a face
    withInterior.emplace_back(1.0, 0.0, 0.5);  // on an edge
    withInterior.push_back(cube[3]);           // duplicate
    const ConvexPiece box = ConvexPiece::hullOf(withInterior);
    expectConsistent(box, withInterior);
    EXPECT_EQ(box.dimension, 3);
    EXPECT_EQ(box.vertices.size(), 8u);
    EXPECT_EQ(box.normals.size(), 6u);
    EXPECT_EQ(box.edges.size(), 12u);
    EXPECT_LT(box.maxViolation(box.centroid), -0.49);

    const std::vector<Vec3> square = {Vec3(0, 0, 2), Vec3(1, 0, 2), Vec3(1, 1, 2), Vec3(0, 1, 2), Vec3(0.5, 0.5, 2)};
    const ConvexPiece flat = ConvexPiece::hullOf(square);
    expectConsistent(flat, square);
    EXPECT_EQ(flat.dimension, 2);
    EXPECT_EQ(flat.vertices.size(), 4u);
    EXPECT_EQ(flat.normals.size(), 6u);
    EXPECT_EQ(flat.edges.size(), 4u);
    EXPECT_LE(flat.maxViolation(Vec3(0.25, 0.75, 2)), 0.0);
    EXPECT_GT(flat.maxViolation(Vec3(0.25, 0.75, 2.001)), 0.0);

    const std::vector<Vec3> line = {Vec3(1, 1, 1), Vec3(3, 1, 1), Vec3(2, 1, 1), Vec3(1.5, 1, 1)};
    const ConvexPiece segment = ConvexPiece::hullOf(line);
    expectConsistent(segment, line);
    EXPECT_EQ(segment.dimension, 1);
    EXPECT_EQ(segment.vertices.size(), 2u);
    EXPECT_EQ(segment.edges.size(), 1u);

    const std::vector<Vec3> same = {Vec3(5, -2, 1e6), Vec3(5, -2, 1e6)};
    const ConvexPiece point = ConvexPiece::hullOf(same);
    expectConsistent(point, same);
    EXPECT_EQ(point.dimension, 0);
    EXPECT_EQ(point.vertices.size(), 1u);
    EXPECT_TRUE(point.edges.empty());

    EXPECT_THROW(ConvexPiece::hullOf({}), std::invalid_argument);
    EXPECT_THROW(ConvexPiece::hullOf({Vec3(0, 0, std::nan(""))}), std::invalid_argument);
}

// Sets just thicker and just thinner than the flatness threshold (1e-11 relative), also far
// from the origin: Qhull or the planar hull, a consistent piece either way.
TEST(ConvexPiece, NearlyFlatSets)
{
    TestRandom rng(8);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (const double thickness : {1e-6, 1e-9, 1e-10, 3e-11, 1e-11, 3e-12, 1e-13, 0.0})
        for (const double offset : {0.0, 1e3})
            for (int i = 0; i < 20; ++i)
            {
                std::vector<Vec3> points;
                for (int k = 0; k < 30; ++k)
                    points.emplace_back(u(rng), u(rng), thickness * u(rng));
                const RigidTransform pose = randomPose(rng, offset * randomUnit(rng));
                for (Vec3 &p : points)
                    p = pose.apply(p);
                const ConvexPiece piece = ConvexPiece::hullOf(points);
                expectConsistent(piece, points);
                EXPECT_EQ(piece.dimension, thickness >= 1e-9 && offset == 0.0 ? 3 : piece.dimension);
                EXPECT_TRUE(piece.dimension == 2 || piece.dimension == 3);
            }
}

TEST(ConvexPiece, RandomHullsContainTheirPointsAtEveryScale)
{
    TestRandom rng(5);
    std::uniform_int_distribution<int> count(4, 60);
    for (const double scale : {1.0, 1e6, 1e-6})
        for (int i = 0; i < 300; ++i)
        {
            const std::vector<Vec3> points = randomCloud(rng, count(rng), scale);
            const ConvexPiece piece = ConvexPiece::hullOf(points);
            expectConsistent(piece, points);
            EXPECT_EQ(piece.dimension, 3);
            EXPECT_LT(piece.maxViolation(piece.centroid), 0.0);
            // Euler: V - E + F = 2 on a polytope whose faces are the merged facets.
            EXPECT_EQ(int(piece.vertices.size()) - int(piece.edges.size()) + int(piece.normals.size()), 2);
            const ConvexPiece moved = piece.transformed(randomPose(rng, scale * randomUnit(rng)));
            for (const Vec3 &v : moved.vertices)
                EXPECT_LE(moved.maxViolation(v), 1e-12 * moved.magnitude());
        }
}

// ---------------------------------------------------------------------------------------------
// The LP against SAT.

TEST(IntersectConvexPieces, AgreesWithSatOnRandomHulls)
{
    TestRandom rng(2024);
    std::uniform_int_distribution<int> count(4, 60);
    const double scales[] = {1.0, 1e6, 1e-6};
    std::vector<ConvexPiece> pools[3];
    for (int s = 0; s < 3; ++s)
        for (int i = 0; i < 400; ++i)
            pools[s].push_back(ConvexPiece::hullOf(randomCloud(rng, count(rng), scales[s])));

    std::uniform_int_distribution<std::size_t> pick(0, 399);
    std::uniform_real_distribution<double> distance(0.0, 1.5);
    Tally all;
    Tally perScale[4];
    const int pairs = hcd::test::cases(100000);
    for (int i = 0; i < pairs; ++i)
    {
        // Five in eight pairs at unit scale; one in eight each huge, tiny, and far from the origin.
        const int variant = i % 8 < 5 ? 0 : i % 8 - 4;
        const int s = variant == 3 ? 0 : variant;
        const double scale = scales[s];
        const Vec3 base = variant == 3 ? Vec3(1e3, -2e3, 5e2) : Vec3::Zero();
        const ConvexPiece a = pools[s][pick(rng)].transformed(randomPose(rng, base));
        const ConvexPiece b =
            pools[s][pick(rng)].transformed(randomPose(rng, base + scale * distance(rng) * randomUnit(rng)));
        Tally one;
        checkPair(a, b, one);
        for (Tally *t : {&all, &perScale[variant]})
        {
            t->pairs += one.pairs, t->intersecting += one.intersecting, t->disagreements += one.disagreements;
            t->nearTouching += one.nearTouching, t->primalDisagreements += one.primalDisagreements;
            t->witnessFailures += one.witnessFailures, t->planeFailures += one.planeFailures;
            for (int c = 0; c < 4; ++c)
                t->byCertificate[c] += one.byCertificate[c];
            t->lpSeconds += one.lpSeconds, t->satSeconds += one.satSeconds;
        }
    }
    perScale[0].print("random, unit scale");
    perScale[1].print("random, scale 1e6");
    perScale[2].print("random, scale 1e-6");
    perScale[3].print("random, unit size at 2e3 from the origin");
    all.print("random, all");
    expectClean(all);
    EXPECT_EQ(all.primalDisagreements, 0);
    const double fraction = double(all.intersecting) / double(all.pairs);
    EXPECT_GT(fraction, 0.2);
    EXPECT_LT(fraction, 0.8);
}

// Random pairs slid along their best separating axis, repeatedly (each slide sets the gap along
// that axis; another may then be the best), until their separating-axis gap is a chosen fraction
// of their size: clearly apart (1e-6), within the tolerance (+-1e-11, 0), clearly overlapping
// (-1e-6). Only the pairs within the tolerance may be answered either way.
TEST(IntersectConvexPieces, RandomPairsSlidToTouching)
{
    TestRandom rng(4242);
    std::uniform_int_distribution<int> count(4, 40);
    const double targets[] = {1e-6, 1e-11, 0.0, -1e-11, -1e-6};
    Tally tallies[5];
    int unconverged = 0;
    for (int i = 0; i < hcd::test::cases(2000); ++i)
    {
        const double scale = i % 3 == 0 ? 1.0 : (i % 3 == 1 ? 1e6 : 1e-6);
        const ConvexPiece a =
            ConvexPiece::hullOf(randomCloud(rng, count(rng), scale)).transformed(randomPose(rng, Vec3::Zero()));
        const ConvexPiece b0 = ConvexPiece::hullOf(randomCloud(rng, count(rng), scale))
                                   .transformed(randomPose(rng, 2.5 * scale * randomUnit(rng)));
        for (int t = 0; t < 5; ++t)
        {
            const double target = targets[t] * scale;
            ConvexPiece b = b0;
            Vec3 axis;
            double gap = separatingAxisGap(a, b, &axis);
            for (int step = 0; step < 100 && std::fabs(gap - target) > 1e-3 * std::fabs(target) + 1e-14 * scale; ++step)
            {
                b = b.transformed({Mat3::Identity(), (target - gap) * axis});
                gap = separatingAxisGap(a, b, &axis);
            }
            if (std::fabs(gap - target) > 1e-3 * std::fabs(target) + 1e-14 * scale)
            {
                ++unconverged;
                continue;
            }
            const bool lp = checkPair(a, b, tallies[t]);
            if (t == 0)
            {
                EXPECT_FALSE(lp);
            }
            if (t == 4)
            {
                EXPECT_TRUE(lp);
            }
        }
    }
    for (int t = 0; t < 5; ++t)
    {
        char name[64];
        std::snprintf(name, sizeof name, "slid to a gap of %g of the size", targets[t]);
        tallies[t].print(name);
        expectClean(tallies[t]);
    }
    std::printf("slides that did not converge (skipped): %d\n", unconverged);
    EXPECT_LT(unconverged, 500);
    EXPECT_EQ(tallies[0].nearTouching, 0);
    EXPECT_EQ(tallies[4].nearTouching, 0);
    EXPECT_EQ(tallies[0].intersecting, 0);
    EXPECT_EQ(tallies[4].intersecting, tallies[4].pairs);
}

// Exactly touching boxes and tetrahedra (dyadic coordinates, so the contact is exact), then the
// same moved apart and pushed together by 2^-20 of their size, at several scales and poses.
TEST(IntersectConvexPieces, TouchingPairs)
{
    const std::vector<Vec3> unitBox = boxCorners(Vec3(0, 0, 0), Vec3(1, 1, 1));
    const std::vector<Vec3> halfBox = boxCorners(Vec3(0, 0, 0), Vec3(0.5, 0.5, 0.5));
    const std::vector<Vec3> tetra = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    struct Contact
    {
        const char *name;
        std::vector<Vec3> a, b;
        Vec3 apart;  // a unit direction that moves b away from a
    };
    const std::vector<Contact> contacts = {
        {"box face", unitBox, shifted(unitBox, Vec3(1, 0, 0)), Vec3(1, 0, 0)},
        {"box face, offset", unitBox, shifted(unitBox, Vec3(1, 0.5, 0.25)), Vec3(1, 0, 0)},
        {"box edge", unitBox, shifted(unitBox, Vec3(1, 1, 0)), Vec3(1, 1, 0).normalized()},
        {"box vertex", unitBox, shifted(unitBox, Vec3(1, 1, 1)), Vec3(1, 1, 1).normalized()},
        {"small box in face", unitBox, shifted(halfBox, Vec3(1, 0.25, 0.25)), Vec3(1, 0, 0)},
        {"tetra vertex-vertex", tetra, {Vec3(2, 0, 0), Vec3(1, 0, 0), Vec3(2, -1, 0), Vec3(2, 0, -1)}, Vec3(1, 0, 0)},
        {"tetra edge-edge",
         tetra,
         {Vec3(0.5, 0.5, -0.5), Vec3(0.5, 0.5, 0.5), Vec3(1, 1, 0), Vec3(1.5, 1, 0.25)},
         Vec3(1, 1, 0).normalized()},
        {"tetra face-face",
         tetra,
         {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)},
         Vec3(1, 1, 1).normalized()},
        {"tetra face on box face", unitBox, shifted(tetra, Vec3(1, 0.25, 0.25)), Vec3(1, 0, 0)},
    };
    TestRandom rng(77);
    Tally touching, apart, together;
    for (const Contact &contact : contacts)
        for (const double scale : {1.0, 1048576.0, 1.0 / 1048576.0, 1e6, 1e-6})
            for (int pose = 0; pose < 40; ++pose)
            {
                // Pose 0 keeps the dyadic coordinates exact; the others rotate and move the pair
                // together (rounding then blurs the contact by ~1e-16 relative).
                const RigidTransform world =
                    pose == 0 ? RigidTransform::identity() : randomPose(rng, scale * randomUnit(rng));
                const ConvexPiece a = ConvexPiece::hullOf(scaled(contact.a, scale)).transformed(world);
                const auto bAt = [&](double move) {
                    return ConvexPiece::hullOf(scaled(shifted(contact.b, move * contact.apart), scale))
                        .transformed(world);
                };
                const double step = 1.0 / 1048576.0;
                EXPECT_TRUE(checkPair(a, bAt(0.0), touching)) << contact.name << " at scale " << scale;
                EXPECT_TRUE(checkPair(bAt(0.0), a, touching)) << contact.name << " at scale " << scale;
                EXPECT_FALSE(checkPair(a, bAt(step), apart)) << contact.name << " at scale " << scale;
                EXPECT_TRUE(checkPair(a, bAt(-step), together)) << contact.name << " at scale " << scale;
            }
    touching.print("touching");
    apart.print("moved apart by 2^-20");
    together.print("pushed together by 2^-20");
    for (const Tally *t : {&touching, &apart, &together})
        expectClean(*t);
}

// A small piece strictly inside a big one, in both orders; identical pieces.
TEST(IntersectConvexPieces, NestedPairs)
{
    TestRandom rng(31);
    Tally nested;
    for (int i = 0; i < hcd::test::cases(2000); ++i)
    {
        // 60 points on the unit sphere: the hull contains the ball of radius 0.5 with certainty
        // far beyond what this test needs; the small piece fits in radius 0.2 around a point
        // within 0.25 of the centre.
        std::vector<Vec3> sphere;
        for (int k = 0; k < 60; ++k)
            sphere.push_back(randomUnit(rng));
        const double scale = i % 3 == 0 ? 1.0 : (i % 3 == 1 ? 1e6 : 1e-6);
        const RigidTransform pose = randomPose(rng, scale * randomUnit(rng));
        const ConvexPiece big = ConvexPiece::hullOf(scaled(sphere, scale)).transformed(pose);
        std::uniform_int_distribution<int> count(4, 20);
        const ConvexPiece small =
            ConvexPiece::hullOf(
                scaled(shifted(scaled(randomCloud(rng, count(rng), 1.0), 0.2), 0.25 * randomInBall(rng)), scale))
                .transformed(pose);
        EXPECT_TRUE(checkPair(big, small, nested));
        const IntersectionResult r = intersectConvexPieces(small, big);
        EXPECT_TRUE(r.intersecting);
        EXPECT_GT(r.depth, 0.0);  // the witness is a centre inside the small piece
        EXPECT_TRUE(checkPair(small, big, nested));
    }
    // Identical pieces, and boxes sharing four face planes (identical rows in the LP).
    for (int i = 0; i < 200; ++i)
    {
        const RigidTransform pose = randomPose(rng, randomUnit(rng));
        std::uniform_int_distribution<int> count(4, 60);
        const ConvexPiece piece = ConvexPiece::hullOf(randomCloud(rng, count(rng), 1.0)).transformed(pose);
        EXPECT_TRUE(checkPair(piece, piece, nested));
        const ConvexPiece box = ConvexPiece::hullOf(boxCorners(Vec3(0, 0, 0), Vec3(1, 1, 1))).transformed(pose);
        const ConvexPiece slid = ConvexPiece::hullOf(boxCorners(Vec3(0.5, 0, 0), Vec3(1.5, 1, 1))).transformed(pose);
        EXPECT_TRUE(checkPair(box, slid, nested));
        EXPECT_TRUE(checkPair(box, box, nested));
    }
    nested.print("nested, identical and coplanar-faced pairs");
    expectClean(nested);
    EXPECT_EQ(nested.intersecting, nested.pairs);
}

// Flat, collinear and single-point pieces against each other and against solids.
TEST(IntersectConvexPieces, FlatAndDegeneratePieces)
{
    TestRandom rng(99);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_int_distribution<int> count(3, 30);
    const auto planar = [&](double radius) {
        std::vector<Vec3> points;
        const int n = count(rng);
        for (int k = 0; k < n; ++k)
            points.emplace_back(radius * u(rng), radius * u(rng), 0.0);
        return points;
    };
    const auto collinear = [&]() {
        std::vector<Vec3> points;
        const double from = u(rng), to = u(rng);
        for (int k = 0; k < 5; ++k)
            points.emplace_back(from + (to - from) * k / 4.0, 0.0, 0.0);
        return points;
    };
    Tally flatSolid, flatFlat, coplanar, lowDim;
    for (int i = 0; i < 4000; ++i)
    {
        const double scale = i % 3 == 0 ? 1.0 : (i % 3 == 1 ? 1e6 : 1e-6);
        const double reach = scale * 0.8 * std::fabs(u(rng));
        const ConvexPiece flat =
            ConvexPiece::hullOf(scaled(planar(1.0), scale)).transformed(randomPose(rng, Vec3::Zero()));
        const ConvexPiece solid = ConvexPiece::hullOf(randomCloud(rng, count(rng) + 1, scale))
                                      .transformed(randomPose(rng, reach * randomUnit(rng)));
        checkPair(flat, solid, flatSolid);
        checkPair(solid, flat, flatSolid);

        const ConvexPiece other =
            ConvexPiece::hullOf(scaled(planar(1.0), scale)).transformed(randomPose(rng, 1.5 * reach * randomUnit(rng)));
        checkPair(flat, other, flatFlat);

        // Two polygons in one plane (same pose, in-plane offset): overlapping or not within it.
        const RigidTransform plane = randomPose(rng, scale * randomUnit(rng));
        const Vec3 inPlane(2.5 * u(rng), 2.5 * u(rng), 0.0);
        checkPair(ConvexPiece::hullOf(scaled(planar(1.0), scale)).transformed(plane),
                  ConvexPiece::hullOf(scaled(shifted(planar(1.0), inPlane), scale)).transformed(plane), coplanar);

        const ConvexPiece segment =
            ConvexPiece::hullOf(scaled(collinear(), scale)).transformed(randomPose(rng, reach * randomUnit(rng)));
        const ConvexPiece segment2 =
            ConvexPiece::hullOf(scaled(collinear(), scale)).transformed(randomPose(rng, reach * randomUnit(rng)));
        const ConvexPiece point = ConvexPiece::hullOf({scale * 0.7 * randomInBall(rng)});
        checkPair(segment, solid, lowDim);
        checkPair(segment, flat, lowDim);
        checkPair(segment, segment2, lowDim);
        checkPair(point, solid, lowDim);
        checkPair(point, flat, lowDim);
        checkPair(point, segment, lowDim);
        checkPair(point, point, lowDim);
    }
    // Exact contacts of degenerate pieces: a segment through a square's centre, a point on a
    // segment, two crossing segments in one plane, a point on a box face, a square on a box face.
    Tally exact;
    const ConvexPiece square = ConvexPiece::hullOf({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)});
    const ConvexPiece pierce = ConvexPiece::hullOf({Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1)});
    const ConvexPiece along = ConvexPiece::hullOf({Vec3(-1, 0.5, 0), Vec3(2, 0.5, 0)});
    const ConvexPiece cross1 = ConvexPiece::hullOf({Vec3(0, 0, 0), Vec3(1, 1, 0)});
    const ConvexPiece cross2 = ConvexPiece::hullOf({Vec3(1, 0, 0), Vec3(0, 1, 0)});
    const ConvexPiece onSegment = ConvexPiece::hullOf({Vec3(0.25, 0.25, 0)});
    const ConvexPiece box = ConvexPiece::hullOf(boxCorners(Vec3(0, 0, -1), Vec3(1, 1, 0)));
    const ConvexPiece onFace = ConvexPiece::hullOf({Vec3(0.5, 0.25, 0)});
    const ConvexPiece offFace = ConvexPiece::hullOf({Vec3(0.5, 0.25, 1.0 / 1048576.0)});
    const ConvexPiece parallel = ConvexPiece::hullOf({Vec3(0, 0, 1.0 / 1048576.0), Vec3(1, 1, 1.0 / 1048576.0)});
    EXPECT_TRUE(checkPair(square, pierce, exact));
    EXPECT_TRUE(checkPair(square, along, exact));
    EXPECT_TRUE(checkPair(cross1, cross2, exact));
    EXPECT_TRUE(checkPair(cross1, onSegment, exact));
    EXPECT_TRUE(checkPair(box, onFace, exact));
    EXPECT_TRUE(checkPair(box, square, exact));
    EXPECT_TRUE(checkPair(square, square, exact));
    EXPECT_FALSE(checkPair(box, offFace, exact));
    EXPECT_FALSE(checkPair(cross1, parallel, exact));
    EXPECT_FALSE(checkPair(onFace, offFace, exact));

    flatSolid.print("flat vs solid");
    flatFlat.print("flat vs flat");
    coplanar.print("coplanar polygons");
    lowDim.print("segments and points");
    exact.print("exact degenerate contacts");
    for (const Tally *t : {&flatSolid, &flatFlat, &coplanar, &lowDim, &exact})
    {
        expectClean(*t);
        EXPECT_EQ(t->primalDisagreements, 0);
    }
}
}  // namespace
}  // namespace hcd
