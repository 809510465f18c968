// SPDX-License-Identifier: BSD-3-Clause
// Micro-benchmarks of the exact LP narrow phase: time per intersection test of two convex
// pieces with 8, 20, 64 and 256 faces (hulls of random points on a sphere, so every point is a
// vertex and a hull of V points has 2V - 4 triangular faces), for the slack LP (4D Seidel, the
// library's test), the review's plain 3D primal feasibility LP, and the separating-axis test.
// The *Warm benchmarks and the dual simplex (eq. 4, dual_lp.h; with the default objective and
// with the review's x + y + z, which needs phase 1) keep one workspace across calls, as a query
// context does, on pieces of 8, 20 and 60 faces; the dual reports its pivots per solve and the
// fraction of answers that fell back to the slack LP.
//
//   build/bench/hybridcd_bench_lp_micro --benchmark_format=json > lp_micro.json
#include "hybridcd/geometry/shape.h"
#include "hybridcd/narrowphase/convex_piece.h"
#include "hybridcd/narrowphase/dual_lp.h"
#include "hybridcd/narrowphase/gjk.h"
#include "hybridcd/narrowphase/linear_program.h"

#include <benchmark/benchmark.h>

#include <map>
#include <random>
#include <utility>
#include <vector>

using namespace hcd;

namespace
{
constexpr std::size_t kPairs = 256;

Mat3 randomRotation(std::mt19937_64 &rng)
{
    std::normal_distribution<double> n;
    return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

Vec3 randomUnit(std::mt19937_64 &rng)
{
    std::normal_distribution<double> n;
    return Vec3(n(rng), n(rng), n(rng)).normalized();
}

// Pairs of pieces with `faces` faces each, the second at a distance uniform in [0, 2.8] from the
// first (radius 1), so that about half of the pairs intersect.
const std::vector<std::pair<ConvexPiece, ConvexPiece>> &piecePairs(int faces)
{
    static std::map<int, std::vector<std::pair<ConvexPiece, ConvexPiece>>> cache;
    auto &pairs = cache[faces];
    if (pairs.empty())
    {
        std::mt19937_64 rng{std::uint64_t(faces)};
        std::uniform_real_distribution<double> distance(0.0, 2.8);
        const auto piece = [&](const Vec3 &at) {
            std::vector<Vec3> points;
            for (int i = 0; i < faces / 2 + 2; ++i)
                points.push_back(randomUnit(rng));
            return ConvexPiece::hullOf(points).transformed({randomRotation(rng), at});
        };
        for (std::size_t i = 0; i < kPairs; ++i)
        {
            ConvexPiece a = piece(Vec3::Zero());
            ConvexPiece b = piece(distance(rng) * randomUnit(rng));
            pairs.emplace_back(std::move(a), std::move(b));
        }
    }
    return pairs;
}

template <typename Test>
void runPairs(benchmark::State &state, Test test)
{
    const auto &pairs = piecePairs(int(state.range(0)));
    std::size_t i = 0, hits = 0, faces = 0;
    for (const auto &p : pairs)
        faces += p.first.normals.size() + p.second.normals.size();
    for (auto _ : state)
    {
        const auto &p = pairs[i % kPairs];
        hits += test(p.first, p.second);
        ++i;
    }
    state.counters["hit fraction"] = double(hits) / double(i);
    state.counters["faces per piece"] = double(faces) / double(2 * kPairs);
}

void BM_LpIntersect(benchmark::State &state)
{
    runPairs(state,
             [](const ConvexPiece &a, const ConvexPiece &b) { return intersectConvexPieces(a, b).intersecting; });
}
BENCHMARK(BM_LpIntersect)->Arg(8)->Arg(20)->Arg(64)->Arg(256);

void BM_PrimalFeasibility(benchmark::State &state)
{
    runPairs(state, [](const ConvexPiece &a, const ConvexPiece &b) { return convexPiecesIntersectPrimal(a, b); });
}
BENCHMARK(BM_PrimalFeasibility)->Arg(8)->Arg(20)->Arg(64)->Arg(256);

void BM_SatIntersect(benchmark::State &state)
{
    runPairs(state, [](const ConvexPiece &a, const ConvexPiece &b) { return convexPiecesIntersectSat(a, b); });
}
BENCHMARK(BM_SatIntersect)->Arg(8)->Arg(20)->Arg(64)->Arg(256);

void BM_LpIntersectWarm(benchmark::State &state)
{
    LpWorkspace workspace;
    runPairs(state, [&](const ConvexPiece &a, const ConvexPiece &b) {
        return intersectConvexPieces(a, b, workspace).intersecting;
    });
}
BENCHMARK(BM_LpIntersectWarm)->Arg(8)->Arg(20)->Arg(60);

void BM_PrimalFeasibilityWarm(benchmark::State &state)
{
    LpWorkspace workspace;
    runPairs(state,
             [&](const ConvexPiece &a, const ConvexPiece &b) { return convexPiecesIntersectPrimal(a, b, workspace); });
}
BENCHMARK(BM_PrimalFeasibilityWarm)->Arg(8)->Arg(20)->Arg(60);

void dualLp(benchmark::State &state, const Vec3 &objective)
{
    DualLpWorkspace workspace;
    runPairs(state, [&](const ConvexPiece &a, const ConvexPiece &b) {
        return intersectConvexPiecesDual(a, b, workspace, objective).intersecting;
    });
    const DualLpWorkspace::Counters &c = workspace.counters();
    state.counters["pivots per solve"] = double(c.pivots) / double(c.solves);
    state.counters["fallback fraction"] = double(c.fallbacks) / double(c.solves);
}

void BM_DualSimplex(benchmark::State &state) { dualLp(state, kDualLpDefaultObjective); }
BENCHMARK(BM_DualSimplex)->Arg(8)->Arg(20)->Arg(60);

void BM_DualSimplexReviewObjective(benchmark::State &state) { dualLp(state, kDualLpReviewObjective); }
BENCHMARK(BM_DualSimplexReviewObjective)->Arg(8)->Arg(20)->Arg(60);
}  // namespace

// GJK on the same pieces as convex shapes (support points by a scan of the vertices): the review's
// §4.6 against its LPs. A fresh warm start per pair, as a first query of a pair would have.
void BM_GjkIntersect(benchmark::State &state)
{
    const auto &pairs = piecePairs(int(state.range(0)));
    std::vector<std::pair<Shape, Shape>> shapes;
    for (const auto &p : pairs)
        shapes.emplace_back(Shape::convex(p.first.vertices), Shape::convex(p.second.vertices));
    GjkRequest request;
    request.stopWhenSeparated = true;
    std::size_t i = 0, hits = 0, iterations = 0;
    for (auto _ : state)
    {
        const auto &p = shapes[i % shapes.size()];
        GjkWarmStart warm;
        const GjkResult result = gjkDistance(GjkBody::placed(p.first, RigidTransform()),
                                             GjkBody::placed(p.second, RigidTransform()), request, warm);
        hits += result.intersecting() ? 1 : 0;
        iterations += std::size_t(result.iterations);
        ++i;
    }
    state.counters["hit fraction"] = double(hits) / double(i);
    state.counters["iterations"] = double(iterations) / double(i);
}
BENCHMARK(BM_GjkIntersect)->Arg(8)->Arg(20)->Arg(60);
