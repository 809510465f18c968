// SPDX-License-Identifier: BSD-3-Clause
// The sweep and prune against the brute-force broad phase: random scenes of 1 to 500 boxes moving
// coherently over many steps, with jumps, adds and removes, coordinates on a coarse grid (so that
// boxes touch and endpoints tie), zero-size boxes, infinite and half-infinite boxes, static bodies
// under the filter, at unit, huge and tiny scales and with sizes spread over twelve decades. At
// every step the two pair sets must be equal, element for element (Coal's self_res[0] ==
// self_res[i]), and so must the answers of one box query.
#include "hybridcd/broadphase/brute_force_broad_phase.h"
#include "hybridcd/broadphase/sweep_and_prune.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

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

constexpr double kInf = std::numeric_limits<double>::infinity();

BroadPhaseBox box(const Vec3 &lower, const Vec3 &upper) { return {lower, upper}; }

std::vector<UserDataPair> pairsOf(const SweepAndPrune &sap)
{
    std::vector<UserDataPair> out;
    sap.overlappingPairs(out);
    return out;
}

TEST(SweepAndPrune, TouchingBoxesOverlapAndApartOnesDoNot)
{
    SweepAndPrune sap;
    sap.add(box(Vec3(0, 0, 0), Vec3(1, 1, 1)), 10);
    sap.add(box(Vec3(1, 0, 0), Vec3(2, 1, 1)), 11);                         // shares a face with 10
    sap.add(box(Vec3(2, 1, 1), Vec3(3, 2, 2)), 12);                         // shares a corner with 11
    sap.add(box(Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, 1)), 13);                 // a point on 10's top face
    sap.add(box(Vec3(5, 5, 5), Vec3(6, 6, 6)), 14);                         // apart from all
    sap.add(box(Vec3(3, 2, 2), Vec3(3, 2, 2)), 15);                         // a point on 12's far corner
    sap.add(box(Vec3(std::nextafter(3.0, 4.0), 2, 2), Vec3(4, 2, 2)), 16);  // one ulp beyond 12
    const std::vector<UserDataPair> expected = {{10, 11}, {10, 13}, {11, 12}, {12, 15}};
    EXPECT_EQ(pairsOf(sap), expected);
    EXPECT_TRUE(sap.validate());

    std::vector<std::uint32_t> hits;
    sap.queryBox(box(Vec3(1, 1, 1), Vec3(1, 1, 1)), hits);  // a corner shared by 10 and 11
    EXPECT_EQ(hits, (std::vector<std::uint32_t>{10, 11}));
    sap.queryBox(box(Vec3(2, 1, 1), Vec3(2, 1, 1)), hits);  // the corner shared by 11 and 12
    EXPECT_EQ(hits, (std::vector<std::uint32_t>{11, 12}));
    sap.queryBox(box(Vec3(4, 4, 4), Vec3(7, 7, 7)), hits);
    EXPECT_EQ(hits, (std::vector<std::uint32_t>{14}));
}

TEST(SweepAndPrune, InfiniteBoxesAndTheFilter)
{
    SweepAndPrune sap;
    BruteForceBroadPhase brute;
    // The floor z <= 0 and a wall x >= 4, both static; a whole-space box from an Aabb with infinite
    // half extents (dynamic); two dynamic boxes.
    const BroadPhaseBox floor = box(Vec3(-kInf, -kInf, -kInf), Vec3(kInf, kInf, 0));
    const BroadPhaseBox wall = box(Vec3(4, -kInf, -kInf), Vec3(kInf, kInf, kInf));
    Aabb everywhere;
    everywhere.halfExtents = Vec3::Constant(kInf);
    const auto addBoth = [&](const BroadPhaseBox &b, std::uint32_t id, BroadPhaseFilter f) {
        sap.add(b, id, f);
        brute.add(b, id, f);
    };
    addBoth(floor, 1, BroadPhaseFilter::staticBody());
    addBoth(wall, 2, BroadPhaseFilter::staticBody());  // meets the floor, but static-static
    sap.add(everywhere, 3);
    brute.add(everywhere, 3);
    addBoth(box(Vec3(0, 0, 0), Vec3(1, 1, 1)), 4, BroadPhaseFilter::dynamicBody());  // touches the floor
    addBoth(box(Vec3(0, 0, 0.5), Vec3(1, 1, 1)), 5, BroadPhaseFilter::dynamicBody());
    const std::vector<UserDataPair> expected = {{1, 3}, {1, 4}, {2, 3}, {3, 4}, {3, 5}, {4, 5}};
    EXPECT_EQ(pairsOf(sap), expected);
    std::vector<UserDataPair> reference;
    brute.overlappingPairs(reference);
    EXPECT_EQ(reference, expected);
    EXPECT_TRUE(sap.validate());

    // A half-space given as an Aabb cannot be (centre -inf, extent inf is NaN): refused.
    Aabb bad;
    bad.center = Vec3(0, 0, -kInf);
    bad.halfExtents = Vec3(1, 1, kInf);
    EXPECT_THROW(sap.add(bad, 9), std::invalid_argument);
    EXPECT_THROW(sap.add(box(Vec3(1, 0, 0), Vec3(0, 1, 1)), 9), std::invalid_argument);
    EXPECT_THROW(brute.add(box(Vec3(0, 0, std::nan("")), Vec3(1, 1, 1)), 9), std::invalid_argument);
    EXPECT_EQ(sap.size(), 5u);
    EXPECT_TRUE(sap.validate());
}

TEST(SweepAndPrune, HandlesAreReusedAfterRemove)
{
    SweepAndPrune sap;
    const BodyHandle a = sap.add(box(Vec3(0, 0, 0), Vec3(1, 1, 1)), 1);
    const BodyHandle b = sap.add(box(Vec3(0, 0, 0), Vec3(1, 1, 1)), 2);
    EXPECT_EQ(sap.pairCount(), 1u);
    sap.remove(a);
    EXPECT_EQ(sap.pairCount(), 0u);
    const BodyHandle c = sap.add(box(Vec3(2, 2, 2), Vec3(3, 3, 3)), 3);
    EXPECT_EQ(c, a);
    EXPECT_EQ(sap.pairCount(), 0u);
    sap.update(c, box(Vec3(1, 1, 1), Vec3(3, 3, 3)));  // now touches b at a corner
    EXPECT_EQ(pairsOf(sap), (std::vector<UserDataPair>{{2, 3}}));
    sap.update(b, box(Vec3(-1, -1, -1), std::nextafter(1.0, 0.0) * Vec3::Ones()));
    EXPECT_EQ(sap.pairCount(), 0u);
    EXPECT_TRUE(sap.validate());
}

// Degenerate scenes: every box the same, every box the same point, a chain of boxes touching end
// to end, all moved together (every endpoint ties with others at every step).
TEST(SweepAndPrune, DegenerateScenes)
{
    const int n = 120;
    for (int scene = 0; scene < 3; ++scene)
    {
        SweepAndPrune sap;
        BruteForceBroadPhase brute;
        std::vector<BodyHandle> a, b;
        const auto boxOf = [&](int i, double shift) {
            const Vec3 s = Vec3::Constant(shift);
            if (scene == 0)
                return box(s, s + Vec3::Ones());
            if (scene == 1)
                return box(s, s);
            return box(s + Vec3(i, 0, 0), s + Vec3(i + 1, 1, 1));  // chain along x
        };
        for (int i = 0; i < n; ++i)
        {
            a.push_back(sap.add(boxOf(i, 0.0), std::uint32_t(i)));
            b.push_back(brute.add(boxOf(i, 0.0), std::uint32_t(i)));
        }
        for (int step = 0; step < 6; ++step)
        {
            std::vector<UserDataPair> fast, reference;
            sap.overlappingPairs(fast);
            brute.overlappingPairs(reference);
            EXPECT_EQ(fast, reference) << "scene " << scene << ", step " << step;
            EXPECT_EQ(fast.size(), scene == 2 ? std::size_t(n - 1) : std::size_t(n * (n - 1) / 2));
            EXPECT_TRUE(sap.validate());
            // Move the bodies together, one by one on even steps, in one batch on odd ones.
            std::vector<BroadPhaseBox> boxes;
            for (int i = 0; i < n; ++i)
            {
                boxes.push_back(boxOf(i, 0.25 * (step + 1)));
                brute.update(b[std::size_t(i)], boxes.back());
                if (step % 2 == 0)
                    sap.update(a[std::size_t(i)], boxes.back());
            }
            if (step % 2 == 1)
                sap.updateMany(a.data(), boxes.data(), a.size());
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Random scenes.

struct SceneOptions
{
    int bodies;        // initial number of bodies
    double scale;      // extent of the scene
    bool grid;         // coordinates on a grid of scale / 16 (ties, touching boxes)
    bool spreadSizes;  // half extents log-uniform over twelve decades
    bool infinite;     // add unbounded bodies
    int steps;
};

struct Mover
{
    BodyHandle sap, brute;
    Vec3 position, half, velocity;
    bool isStatic;
    int kind;  // 0 finite, 1 floor (z <= top), 2 slab unbounded in x, 3 everything
};

struct Stats
{
    long steps = 0, reportedPairs = 0, candidatePairs = 0, touchingPairs = 0, queries = 0, queryHits = 0,
         emptyQueries = 0;
    long mismatches = 0;
};

class Scene
{
public:
    Scene(const SceneOptions &o, std::uint64_t seed) : o_(o), rng_(seed) {}

    void run(Stats &stats)
    {
        for (int i = 0; i < o_.bodies; ++i)
            addRandom();
        if (o_.infinite)
            for (int kind = 1; kind <= 3; ++kind)
                addInfinite(kind);
        compare(stats);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (int step = 0; step < o_.steps; ++step)
        {
            // Odd steps move the bodies through updateMany (one batch), even steps one by one;
            // every third odd step moves only a few bodies (the batch then updates one by one).
            const bool batch = step % 2 == 1;
            const bool few = step % 6 == 1;
            std::vector<BodyHandle> handles;
            std::vector<BroadPhaseBox> boxes;
            for (Mover &m : movers_)
            {
                if (m.isStatic)
                    continue;
                if (u(rng_) < 0.01)  // a jump across the scene
                    m.position = randomPoint();
                else
                    m.position += m.velocity;
                if (u(rng_) < 0.05)
                    m.velocity = randomVelocity();
                if (u(rng_) < 0.02)
                    m.half = randomHalf();
                if (few && u(rng_) < 0.9)
                    continue;
                const BroadPhaseBox b = boxOf(m);
                if (batch)
                    handles.push_back(m.sap), boxes.push_back(b);
                else
                    sap_.update(m.sap, b);
                brute_.update(m.brute, b);
            }
            if (batch)
                sap_.updateMany(handles.data(), boxes.data(), handles.size());
            // Occasional removes and adds (the scene size drifts but stays near its start).
            if (!movers_.empty() && u(rng_) < 0.3)
            {
                std::uniform_int_distribution<std::size_t> pick(0, movers_.size() - 1);
                const std::size_t i = pick(rng_);
                sap_.remove(movers_[i].sap);
                brute_.remove(movers_[i].brute);
                movers_[i] = movers_.back();
                movers_.pop_back();
            }
            if (u(rng_) < 0.3 || movers_.empty())
                addRandom();
            compare(stats);
            if (step % 16 == 0 && movers_.size() <= 200)
            {
                EXPECT_TRUE(sap_.validate());
            }
        }
    }

private:
    double snap(double v) const
    {
        if (!o_.grid)
            return v;
        const double q = o_.scale / 16.0;
        return std::round(v / q) * q;
    }
    Vec3 randomPoint()
    {
        std::uniform_real_distribution<double> u(-o_.scale, o_.scale);
        return Vec3(snap(u(rng_)), snap(u(rng_)), snap(u(rng_)));
    }
    Vec3 randomVelocity()
    {
        std::uniform_real_distribution<double> u(-0.02 * o_.scale, 0.02 * o_.scale);
        Vec3 v(u(rng_), u(rng_), u(rng_));
        if (o_.grid)  // whole grid steps (or none) so positions stay on the grid
            v = (v / (o_.scale / 16.0)).array().round() * (o_.scale / 16.0);
        return v;
    }
    Vec3 randomHalf()
    {
        std::uniform_real_distribution<double> u(0.0, 1.0);
        if (u(rng_) < 0.1)
            return Vec3::Zero();  // a point box
        Vec3 h;
        for (int k = 0; k < 3; ++k)
        {
            if (o_.spreadSizes)
                h[k] = o_.scale * 0.2 * std::pow(10.0, -12.0 * u(rng_));
            else
                h[k] = snap(o_.scale * 0.25 * u(rng_));
            if (u(rng_) < 0.05)
                h[k] = 0.0;  // flat along one axis
        }
        return h;
    }
    BroadPhaseBox boxOf(const Mover &m) const
    {
        switch (m.kind)
        {
        case 1:
            return box(Vec3(-kInf, -kInf, -kInf), Vec3(kInf, kInf, m.position.z()));
        case 2:
            return box(Vec3(-kInf, m.position.y() - m.half.y(), m.position.z() - m.half.z()),
                       Vec3(kInf, m.position.y() + m.half.y(), m.position.z() + m.half.z()));
        case 3:
            return box(Vec3::Constant(-kInf), Vec3::Constant(kInf));
        default:
            return box(m.position - m.half, m.position + m.half);
        }
    }
    void addMover(Mover m)
    {
        const BroadPhaseBox b = boxOf(m);
        const BroadPhaseFilter f = m.isStatic ? BroadPhaseFilter::staticBody() : BroadPhaseFilter::dynamicBody();
        const std::uint32_t id = nextId_++;
        // Half of the finite bodies go in as Aabb, to cover that path as well.
        if (m.kind == 0 && id % 2 == 0)
        {
            Aabb a;
            a.center = m.position;
            a.halfExtents = m.half;
            m.sap = sap_.add(a, id, f);
            m.brute = brute_.add(a, id, f);
        }
        else
        {
            m.sap = sap_.add(b, id, f);
            m.brute = brute_.add(b, id, f);
        }
        movers_.push_back(m);
    }
    void addRandom()
    {
        std::uniform_real_distribution<double> u(0.0, 1.0);
        addMover({{}, {}, randomPoint(), randomHalf(), randomVelocity(), u(rng_) < 0.3, 0});
    }
    void addInfinite(int kind)
    {
        // The floor and the slab move (their finite sides sweep through the scene); "everything"
        // is static, so it pairs only with dynamic bodies.
        addMover({{}, {}, randomPoint(), randomHalf(), randomVelocity(), kind == 3, kind});
    }

    void compare(Stats &stats)
    {
        std::vector<UserDataPair> fast, reference;
        sap_.overlappingPairs(fast);
        brute_.overlappingPairs(reference);
        ++stats.steps;
        stats.reportedPairs += long(reference.size());
        const long n = long(movers_.size());
        stats.candidatePairs += n * (n - 1) / 2;
        if (fast != reference)
        {
            if (stats.mismatches++ < 5)
                ADD_FAILURE() << "pair sets differ at step " << stats.steps << ": sweep and prune " << fast.size()
                              << " pairs, brute force " << reference.size() << " (bodies " << n << ", scale "
                              << o_.scale << ")";
        }
        // Touching pairs among the reported ones: some axis where the boxes only meet.
        for (const Mover &a : movers_)
            for (const Mover &b : movers_)
            {
                if (&a >= &b)
                    continue;
                const BroadPhaseBox x = boxOf(a), y = boxOf(b);
                if (!broadPhaseBoxesOverlap(x, y))
                    continue;
                bool touching = false;
                for (int k = 0; k < 3; ++k)
                    touching = touching || x.upper[k] == y.lower[k] || y.upper[k] == x.lower[k];
                stats.touchingPairs += touching;
            }
        // One box query per step.
        std::uniform_real_distribution<double> u(0.0, 1.0);
        const Vec3 p = randomPoint(), h = randomHalf();
        const BroadPhaseBox q = box(p - h, p + h);
        const BroadPhaseFilter filter =
            u(rng_) < 0.5 ? BroadPhaseFilter::everything() : BroadPhaseFilter::dynamicBody();
        std::vector<std::uint32_t> fastHits, referenceHits;
        sap_.queryBox(q, fastHits, filter);
        brute_.queryBox(q, referenceHits, filter);
        ++stats.queries;
        stats.queryHits += long(referenceHits.size());
        stats.emptyQueries += referenceHits.empty();
        if (fastHits != referenceHits && stats.mismatches++ < 5)
            ADD_FAILURE() << "box query differs at step " << stats.steps;
    }

    SceneOptions o_;
    TestRandom rng_;
    SweepAndPrune sap_;
    BruteForceBroadPhase brute_;
    std::vector<Mover> movers_;
    std::uint32_t nextId_ = 0;
};

void expectInformative(const Stats &s, const char *name, bool expectTouching)
{
    std::printf("[%s] steps %ld, reported pairs %ld of %ld candidate pairs (%.2f%%), touching %ld, query hits %ld "
                "over %ld queries, %ld of them empty\n",
                name, s.steps, s.reportedPairs, s.candidatePairs,
                s.candidatePairs ? 100.0 * double(s.reportedPairs) / double(s.candidatePairs) : 0.0, s.touchingPairs,
                s.queryHits, s.queries, s.emptyQueries);
    EXPECT_EQ(s.mismatches, 0);
    // The generator is informative: both overlapping and apart pairs, and query hits and misses.
    EXPECT_GT(s.reportedPairs, 0);
    EXPECT_GT(s.candidatePairs - s.reportedPairs, s.reportedPairs / 10);
    EXPECT_GT(s.queryHits, 0);
    EXPECT_GT(s.emptyQueries, 0);
    if (expectTouching)
    {
        EXPECT_GT(s.touchingPairs, 0);
    }
}

void runScenes(const char *name, SceneOptions o, std::uint64_t seed, bool expectTouching)
{
    Stats stats;
    for (const int bodies : {1, 2, 3, 10, 60, 200, 500})
    {
        o.bodies = bodies;
        o.steps = bodies >= 200 ? test::cases(40) : test::cases(150);
        const int repeats = bodies <= 10 ? test::cases(20) : 1;
        for (int r = 0; r < repeats; ++r)
            Scene(o, test::seeded(seed + std::uint64_t(1000 * bodies + r))).run(stats);
    }
    expectInformative(stats, name, expectTouching);
}

TEST(SweepAndPrune, MatchesBruteForceOnGridScenes)
{
    // Coordinates on a grid: equal endpoints, touching and zero-size boxes all the time.
    runScenes("grid, unit scale", {0, 1.0, true, false, false, 0}, 1, true);
    runScenes("grid, scale 1e12", {0, 1e12, true, false, true, 0}, 2, true);
    runScenes("grid, scale 1e-12", {0, 1e-12, true, false, true, 0}, 3, true);
}

TEST(SweepAndPrune, MatchesBruteForceOnContinuousScenes)
{
    runScenes("continuous, unit scale, infinite bodies", {0, 1.0, false, false, true, 0}, 4, false);
    runScenes("continuous, sizes over twelve decades", {0, 1.0, false, true, true, 0}, 5, false);
    runScenes("continuous, scale 1e9", {0, 1e9, false, false, false, 0}, 6, false);
}
}  // namespace
}  // namespace hcd
