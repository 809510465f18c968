// SPDX-License-Identifier: BSD-3-Clause
// The dual simplex (eq. 4 of the review) against the slack LP (intersectConvexPieces) and the
// separating-axis test, on random hull pairs at unit, huge and tiny scales and on adversarial
// pairs: exactly touching faces, edges and vertices (dyadic coordinates), containment both ways,
// identical pieces and coplanar faces, flat pieces (triangles and polygons), segments and points.
// Every pair is solved with three objectives (the default, the review's x + y + z, which needs
// phase 1, and a random one), and every answer's certificate is checked: the witness against both
// pieces' inequalities, the separating plane against both pieces' vertices.
#include "hybridcd/narrowphase/convex_piece.h"
#include "hybridcd/narrowphase/dual_lp.h"
#include "hybridcd/narrowphase/linear_program.h"
#include "hybridcd/narrowphase/separating_axes.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

// Counts every allocation of the program, so a test can check that a warm solve makes none. (GCC
// takes the inlined standard allocator's delete for a mismatch with this malloc-based new.)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
static std::atomic<long> allocations{0};
void *operator new(std::size_t size)
{
    ++allocations;
    if (void *p = std::malloc(size ? size : 1))
        return p;
    throw std::bad_alloc();
}
void operator delete(void *p) noexcept { std::free(p); }
void operator delete(void *p, std::size_t) noexcept { std::free(p); }

namespace hcd
{
namespace
{
using test::TestRandom;

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

std::string describe(const ConvexPiece &a, const ConvexPiece &b)
{
    char text[200];
    std::snprintf(text, sizeof text, "dims %d/%d, faces %zu/%zu, vertices %zu/%zu, magnitude %.3g", a.dimension,
                  b.dimension, a.normals.size(), b.normals.size(), a.vertices.size(), b.vertices.size(),
                  std::max(a.magnitude(), b.magnitude()));
    return text;
}

struct Tally
{
    long solves = 0, pairs = 0, intersecting = 0;
    long slackDisagreements = 0;  // the dual's verdict differs from intersectConvexPieces'
    long satDisagreements = 0;    // differs from SAT, and the pair is not within 2x the tolerance of touching
    long nearTouching = 0;        // differs from SAT within the tolerance band (as the slack LP may)
    long witnessFailures = 0, planeFailures = 0;
    long byCertificate[3] = {0, 0, 0};
    long pivots = 0;

    void add(const Tally &o)
    {
        solves += o.solves, pairs += o.pairs, intersecting += o.intersecting;
        slackDisagreements += o.slackDisagreements, satDisagreements += o.satDisagreements;
        nearTouching += o.nearTouching, witnessFailures += o.witnessFailures, planeFailures += o.planeFailures;
        for (int c = 0; c < 3; ++c)
            byCertificate[c] += o.byCertificate[c];
        pivots += o.pivots;
    }

    void print(const char *name) const
    {
        std::printf("[%s] pairs %ld (solves %ld), intersecting %ld (%.1f%%), disagreements with the slack LP %ld, "
                    "with SAT %ld (near touching %ld), witness failures %ld, plane failures %ld; certificates: "
                    "witness %ld, Farkas plane %ld, fallback %ld; %.2f pivots per solve\n",
                    name, pairs, solves, intersecting, pairs ? 100.0 * double(intersecting) / double(pairs) : 0.0,
                    slackDisagreements, satDisagreements, nearTouching, witnessFailures, planeFailures,
                    byCertificate[0], byCertificate[1], byCertificate[2],
                    solves ? double(pivots) / double(solves) : 0.0);
    }
};

void expectClean(const Tally &t)
{
    EXPECT_EQ(t.slackDisagreements, 0);
    EXPECT_EQ(t.satDisagreements, 0);
    EXPECT_EQ(t.witnessFailures, 0);
    EXPECT_EQ(t.planeFailures, 0);
    // The dual answers (nearly) everything itself: the fallback is for rounding trouble only.
    EXPECT_LE(t.byCertificate[2], t.solves / 50);
}

// Solves the pair with three objectives, checks each certificate and compares the verdicts with
// the slack LP and SAT. Returns the dual's verdict (the same for all three, or a failure).
bool checkPair(const ConvexPiece &a, const ConvexPiece &b, Tally &tally, TestRandom &rng)
{
    static DualLpWorkspace workspace;  // one warm workspace, as a caller keeps one
    const double tolerance = kNarrowPhaseRelativeTolerance * std::max(a.magnitude(), b.magnitude());
    const IntersectionResult slack = intersectConvexPieces(a, b);
    const bool sat = convexPiecesIntersectSat(a, b);
    std::normal_distribution<double> n;
    const Vec3 objectives[3] = {kDualLpDefaultObjective, kDualLpReviewObjective, Vec3(n(rng), n(rng), n(rng))};
    ++tally.pairs;
    bool verdict = false;
    for (int o = 0; o < 3; ++o)
    {
        const DualLpResult dual = intersectConvexPiecesDual(a, b, workspace, objectives[o]);
        ++tally.solves;
        tally.pivots += dual.pivots;
        ++tally.byCertificate[int(dual.certificate)];
        if (o == 0)
        {
            verdict = dual.intersecting;
            tally.intersecting += dual.intersecting;
        }
        if (dual.intersecting)
        {
            const double violation = std::max(a.maxViolation(dual.witness), b.maxViolation(dual.witness));
            if (!(violation <= tolerance) && tally.witnessFailures++ < 10)
                ADD_FAILURE() << "witness violates an inequality by " << violation << " (tolerance " << tolerance
                              << "), " << describe(a, b);
        }
        else
        {
            bool separates = std::abs(dual.separatingNormal.norm() - 1.0) < 1e-12;
            for (const Vec3 &v : a.vertices)
                separates = separates && dual.separatingNormal.dot(v) <= dual.separatingOffset;
            for (const Vec3 &v : b.vertices)
                separates = separates && dual.separatingNormal.dot(v) >= dual.separatingOffset;
            if (!separates && tally.planeFailures++ < 10)
                ADD_FAILURE() << "separating plane fails on a vertex, " << describe(a, b);
        }
        if (dual.intersecting != slack.intersecting && tally.slackDisagreements++ < 10)
            ADD_FAILURE() << "dual " << dual.intersecting << ", slack LP " << slack.intersecting << ", objective " << o
                          << ", certificate " << int(dual.certificate) << ", SAT gap " << separatingAxisGap(a, b)
                          << ", tolerance " << tolerance << ", " << describe(a, b);
        if (dual.intersecting != sat)
        {
            const double gap = separatingAxisGap(a, b);
            const bool near = std::fabs(gap) <= 2.0 * tolerance || std::fabs(slack.depth) <= 2.0 * tolerance;
            (near ? tally.nearTouching : tally.satDisagreements) += 1;
        }
    }
    return verdict;
}

TEST(DualLp, AgreesWithSlackLpAndSatOnRandomHulls)
{
    TestRandom rng(test::seeded(2025));
    std::uniform_int_distribution<int> count(4, 60);
    const double scales[] = {1.0, 1e6, 1e-6};
    std::vector<ConvexPiece> pools[3];
    for (int s = 0; s < 3; ++s)
        for (int i = 0; i < 300; ++i)
            pools[s].push_back(ConvexPiece::hullOf(randomCloud(rng, count(rng), scales[s])));
    std::uniform_int_distribution<std::size_t> pick(0, 299);
    std::uniform_real_distribution<double> distance(0.0, 1.5);
    Tally perVariant[4], all;
    for (int i = 0; i < test::cases(6000); ++i)
    {
        // Five in eight pairs at unit scale; one in eight each huge, tiny, and far from the origin.
        const int variant = i % 8 < 5 ? 0 : i % 8 - 4;
        const int s = variant == 3 ? 0 : variant;
        const Vec3 base = variant == 3 ? Vec3(1e3, -2e3, 5e2) : Vec3::Zero();
        const ConvexPiece a = pools[s][pick(rng)].transformed(randomPose(rng, base));
        const ConvexPiece b =
            pools[s][pick(rng)].transformed(randomPose(rng, base + scales[s] * distance(rng) * randomUnit(rng)));
        checkPair(a, b, perVariant[variant], rng);
    }
    const char *names[] = {"random, unit scale", "random, scale 1e6", "random, scale 1e-6",
                           "random, unit size at 2e3 from the origin"};
    for (int v = 0; v < 4; ++v)
    {
        perVariant[v].print(names[v]);
        all.add(perVariant[v]);
    }
    expectClean(all);
    // The generator is informative: between 30% and 70% of the pairs intersect.
    const double hitRate = double(all.intersecting) / double(all.pairs);
    EXPECT_GT(hitRate, 0.3);
    EXPECT_LT(hitRate, 0.7);
    // The dual answers nearly everything itself (the fallback is for rounding trouble).
    EXPECT_LT(all.byCertificate[2], all.solves / 100);
}

// Exactly touching boxes and tetrahedra (dyadic coordinates), then moved apart and pushed together
// by 2^-20 of their size, at several scales and poses.
TEST(DualLp, TouchingPairs)
{
    const std::vector<Vec3> unitBox = boxCorners(Vec3(0, 0, 0), Vec3(1, 1, 1));
    const std::vector<Vec3> halfBox = boxCorners(Vec3(0, 0, 0), Vec3(0.5, 0.5, 0.5));
    const std::vector<Vec3> tetra = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    struct Contact
    {
        const char *name;
        std::vector<Vec3> a, b;
        Vec3 apart;
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
    TestRandom rng(test::seeded(77));
    Tally touching, apart, together;
    for (const Contact &contact : contacts)
        for (const double scale : {1.0, 1048576.0, 1.0 / 1048576.0, 1e6, 1e-6})
            for (int pose = 0; pose < 20; ++pose)
            {
                const RigidTransform world =
                    pose == 0 ? RigidTransform::identity() : randomPose(rng, scale * randomUnit(rng));
                const ConvexPiece a = ConvexPiece::hullOf(scaled(contact.a, scale)).transformed(world);
                const auto bAt = [&](double move) {
                    return ConvexPiece::hullOf(scaled(shifted(contact.b, move * contact.apart), scale))
                        .transformed(world);
                };
                const double step = 1.0 / 1048576.0;
                EXPECT_TRUE(checkPair(a, bAt(0.0), touching, rng)) << contact.name << " at scale " << scale;
                EXPECT_TRUE(checkPair(bAt(0.0), a, touching, rng)) << contact.name << " at scale " << scale;
                EXPECT_FALSE(checkPair(a, bAt(step), apart, rng)) << contact.name << " at scale " << scale;
                EXPECT_TRUE(checkPair(a, bAt(-step), together, rng)) << contact.name << " at scale " << scale;
            }
    touching.print("touching");
    apart.print("moved apart by 2^-20");
    together.print("pushed together by 2^-20");
    for (const Tally *t : {&touching, &apart, &together})
        expectClean(*t);
}

// A small piece inside a big one in both orders; identical pieces; boxes sharing face planes.
TEST(DualLp, ContainmentIdenticalAndCoplanarFaces)
{
    TestRandom rng(test::seeded(31));
    Tally nested;
    for (int i = 0; i < test::cases(600); ++i)
    {
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
        EXPECT_TRUE(checkPair(big, small, nested, rng));
        EXPECT_TRUE(checkPair(small, big, nested, rng));
    }
    for (int i = 0; i < 200; ++i)
    {
        const RigidTransform pose = randomPose(rng, randomUnit(rng));
        std::uniform_int_distribution<int> count(4, 60);
        const ConvexPiece piece = ConvexPiece::hullOf(randomCloud(rng, count(rng), 1.0)).transformed(pose);
        EXPECT_TRUE(checkPair(piece, piece, nested, rng));
        const ConvexPiece box = ConvexPiece::hullOf(boxCorners(Vec3(0, 0, 0), Vec3(1, 1, 1))).transformed(pose);
        const ConvexPiece slid = ConvexPiece::hullOf(boxCorners(Vec3(0.5, 0, 0), Vec3(1.5, 1, 1))).transformed(pose);
        EXPECT_TRUE(checkPair(box, slid, nested, rng));
        EXPECT_TRUE(checkPair(box, box, nested, rng));
    }
    nested.print("nested, identical and coplanar-faced pairs");
    expectClean(nested);
    EXPECT_EQ(nested.intersecting, nested.pairs);
}

// Triangles and polygons against solids and each other (also in one plane), segments and points,
// and exact degenerate contacts.
TEST(DualLp, FlatAndDegeneratePieces)
{
    TestRandom rng(test::seeded(99));
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_int_distribution<int> count(3, 30);
    const auto planar = [&](double radius, int n) {
        std::vector<Vec3> points;
        for (int k = 0; k < n; ++k)
            points.emplace_back(radius * u(rng), radius * u(rng), 0.0);
        return points;
    };
    Tally flatSolid, flatFlat, coplanar, lowDim;
    for (int i = 0; i < test::cases(1500); ++i)
    {
        const double scale = i % 3 == 0 ? 1.0 : (i % 3 == 1 ? 1e6 : 1e-6);
        const double reach = scale * 0.8 * std::fabs(u(rng));
        const int corners = i % 2 == 0 ? 3 : count(rng);  // triangles half of the time
        const ConvexPiece flat =
            ConvexPiece::hullOf(scaled(planar(1.0, corners), scale)).transformed(randomPose(rng, Vec3::Zero()));
        const ConvexPiece solid = ConvexPiece::hullOf(randomCloud(rng, count(rng) + 1, scale))
                                      .transformed(randomPose(rng, reach * randomUnit(rng)));
        checkPair(flat, solid, flatSolid, rng);
        checkPair(solid, flat, flatSolid, rng);
        const ConvexPiece other = ConvexPiece::hullOf(scaled(planar(1.0, 3), scale))
                                      .transformed(randomPose(rng, 1.5 * reach * randomUnit(rng)));
        checkPair(flat, other, flatFlat, rng);
        const RigidTransform plane = randomPose(rng, scale * randomUnit(rng));
        const Vec3 inPlane(2.5 * u(rng), 2.5 * u(rng), 0.0);
        checkPair(ConvexPiece::hullOf(scaled(planar(1.0, corners), scale)).transformed(plane),
                  ConvexPiece::hullOf(scaled(shifted(planar(1.0, 3), inPlane), scale)).transformed(plane), coplanar,
                  rng);
        const ConvexPiece point = ConvexPiece::hullOf({scale * 0.7 * randomInBall(rng)});
        const ConvexPiece segment = ConvexPiece::hullOf({scale * randomInBall(rng), scale * randomInBall(rng)})
                                        .transformed(randomPose(rng, reach * randomUnit(rng)));
        checkPair(segment, solid, lowDim, rng);
        checkPair(segment, flat, lowDim, rng);
        checkPair(point, solid, lowDim, rng);
        checkPair(point, flat, lowDim, rng);
    }
    Tally exact;
    const ConvexPiece square = ConvexPiece::hullOf({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)});
    const ConvexPiece triangle = ConvexPiece::hullOf({Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(1, 1, 0)});  // shares an edge
    const ConvexPiece pierce = ConvexPiece::hullOf({Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1)});
    const ConvexPiece box = ConvexPiece::hullOf(boxCorners(Vec3(0, 0, -1), Vec3(1, 1, 0)));
    const ConvexPiece onFace = ConvexPiece::hullOf({Vec3(0.5, 0.25, 0)});
    const ConvexPiece offFace = ConvexPiece::hullOf({Vec3(0.5, 0.25, 1.0 / 1048576.0)});
    const ConvexPiece cornerTriangle = ConvexPiece::hullOf({Vec3(1, 1, 0), Vec3(2, 1, 0), Vec3(1, 2, 1)});
    EXPECT_TRUE(checkPair(square, triangle, exact, rng));
    EXPECT_TRUE(checkPair(square, pierce, exact, rng));
    EXPECT_TRUE(checkPair(box, onFace, exact, rng));
    EXPECT_TRUE(checkPair(box, square, exact, rng));
    EXPECT_TRUE(checkPair(box, cornerTriangle, exact, rng));  // a shared vertex only
    EXPECT_FALSE(checkPair(box, offFace, exact, rng));
    flatSolid.print("flat vs solid");
    flatFlat.print("flat vs flat");
    coplanar.print("coplanar polygons");
    lowDim.print("segments and points");
    exact.print("exact degenerate contacts");
    for (const Tally *t : {&flatSolid, &flatFlat, &coplanar, &lowDim, &exact})
        expectClean(*t);
}

// The workspace counts solves, pivots and fallbacks, and phase 1 runs only for positive
// objective components.
TEST(DualLp, CountersAndPhaseOne)
{
    DualLpWorkspace ws;
    const ConvexPiece a = ConvexPiece::hullOf(boxCorners(Vec3(0, 0, 0), Vec3(1, 1, 1)));
    const ConvexPiece b = ConvexPiece::hullOf(boxCorners(Vec3(0.5, 0.5, 0.5), Vec3(2, 2, 2)));
    const ConvexPiece c = ConvexPiece::hullOf(boxCorners(Vec3(3, 0, 0), Vec3(4, 1, 1)));
    DualLpResult r = intersectConvexPiecesDual(a, b, ws);
    EXPECT_TRUE(r.intersecting);
    EXPECT_EQ(r.certificate, DualLpResult::Certificate::Witness);
    EXPECT_EQ(ws.counters().phaseOnePivots, 0u);
    r = intersectConvexPiecesDual(a, c, ws);
    EXPECT_FALSE(r.intersecting);
    EXPECT_EQ(r.certificate, DualLpResult::Certificate::FarkasPlane);
    EXPECT_NEAR(r.separatingNormal.x(), 1.0, 1e-12);
    r = intersectConvexPiecesDual(a, b, ws, kDualLpReviewObjective);
    EXPECT_TRUE(r.intersecting);
    EXPECT_GT(ws.counters().phaseOnePivots, 0u);
    // With the review's objective the witness maximises x + y + z over the intersection: (1, 1, 1).
    EXPECT_NEAR((r.witness - Vec3(1, 1, 1)).norm(), 0.0, 1e-12);
    EXPECT_EQ(ws.counters().solves, 3u);
    EXPECT_EQ(ws.counters().fallbacks, 0u);
    EXPECT_GT(ws.counters().pivots, 0u);
}
// Once a workspace has seen the largest pair, solving allocates nothing (both objectives, hits
// and misses).
TEST(DualLp, WarmSolvesDoNotAllocate)
{
    TestRandom rng(test::seeded(12));
    std::vector<std::pair<ConvexPiece, ConvexPiece>> pairs;
    for (int i = 0; i < 200; ++i)
        pairs.emplace_back(
            ConvexPiece::hullOf(randomCloud(rng, 40, 1.0)),
            ConvexPiece::hullOf(randomCloud(rng, 40, 1.0)).transformed(randomPose(rng, 1.2 * randomInBall(rng))));
    DualLpWorkspace ws;
    for (const auto &p : pairs)  // warm up
        intersectConvexPiecesDual(p.first, p.second, ws);
    int hits = 0;
    const long before = allocations.load();
    for (const auto &p : pairs)
    {
        hits += intersectConvexPiecesDual(p.first, p.second, ws).intersecting;
        hits += intersectConvexPiecesDual(p.first, p.second, ws, kDualLpReviewObjective).intersecting;
    }
    EXPECT_EQ(allocations.load() - before, 0);
    EXPECT_GT(hits, 0);
    EXPECT_LT(hits, 400);
}
}  // namespace
}  // namespace hcd
