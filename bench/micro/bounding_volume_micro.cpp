// SPDX-License-Identifier: BSD-3-Clause
// Micro-benchmarks of the primitives every query is made of: the OBB separating-axis test, the
// exact triangle-triangle test (generic and coplanar inputs), the orientation predicate; and, for
// every volume of the trees, one node-pair test and one robot-node placement (BM_Volume*).
//
//   build/bench/hybridcd_bench_micro --benchmark_format=json > micro.json
#include "hybridcd/bv/ellipsoid.h"
#include "hybridcd/bv/minimum_volume_ellipsoid.h"
#include "hybridcd/bv/obb.h"
#include "hybridcd/bvh/volume_traits.h"
#include "hybridcd/geometry/exact_predicates.h"
#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/query/placed_robot.h"

#include <benchmark/benchmark.h>

#include <random>

using namespace hcd;

namespace
{
std::mt19937_64 rng(1);

Mat3 randomRotation()
{
    std::normal_distribution<double> n;
    return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

struct TrianglePair
{
    Vec3 a[3], b[3];
};

std::vector<TrianglePair> randomPairs(std::size_t n, double spread, bool coplanar)
{
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<TrianglePair> v(n);
    for (auto &p : v)
        for (int k = 0; k < 3; ++k)
        {
            p.a[k] = Vec3(u(rng), u(rng), coplanar ? 0.0 : u(rng));
            p.b[k] = Vec3(u(rng) * spread, u(rng) * spread, coplanar ? 0.0 : u(rng) * spread);
        }
    return v;
}

void BM_ObbOverlap(benchmark::State &state)
{
    std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.1, 1.0);
    std::vector<std::pair<Obb, Obb>> boxes(1024);
    std::vector<RigidTransform> poses(1024);
    for (std::size_t i = 0; i < boxes.size(); ++i)
    {
        boxes[i].first = {Vec3::Zero(), randomRotation(), Vec3(e(rng), e(rng), e(rng))};
        boxes[i].second = {Vec3(u(rng), u(rng), u(rng)) * 2.0, randomRotation(), Vec3(e(rng), e(rng), e(rng))};
        poses[i] = {randomRotation(), Vec3(u(rng), u(rng), u(rng))};
    }
    std::size_t i = 0, hits = 0;
    for (auto _ : state)
    {
        const auto &b = boxes[i & 1023];
        hits += obbsOverlap(b.first, poses[i & 1023], b.second, 1e-12);
        ++i;
    }
    state.counters["overlap fraction"] = double(hits) / double(i);
}
BENCHMARK(BM_ObbOverlap);

// The same kind of random pairs as BM_ObbOverlap (random axes, extents 0.1..1, centres within 2).
void BM_EllipsoidOverlap(benchmark::State &state)
{
    std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.1, 1.0);
    std::vector<std::pair<Ellipsoid, Ellipsoid>> pairs(1024);
    for (auto &p : pairs)
    {
        p.first = Ellipsoid::fromAxes(Vec3::Zero(), randomRotation(), Vec3(e(rng), e(rng), e(rng)));
        p.second =
            Ellipsoid::fromAxes(Vec3(u(rng), u(rng), u(rng)) * 2.0, randomRotation(), Vec3(e(rng), e(rng), e(rng)));
    }
    std::size_t i = 0, hits = 0;
    for (auto _ : state)
    {
        const auto &p = pairs[i & 1023];
        hits += ellipsoidsOverlap(p.first, p.second);
        ++i;
    }
    state.counters["overlap fraction"] = double(hits) / double(i);
}
BENCHMARK(BM_EllipsoidOverlap);

// MVEE of a random cloud of `range(0)` points (hull candidates, cardinality reduction, tolerance 1e-3).
void BM_MveeFit(benchmark::State &state)
{
    std::normal_distribution<double> n;
    std::vector<Vec3> points(std::size_t(state.range(0)));
    for (auto &p : points)
        p = Vec3(3.0 * n(rng), n(rng), 0.5 * n(rng));
    for (auto _ : state)
        benchmark::DoNotOptimize(fitMinimumVolumeEllipsoid(points));
}
BENCHMARK(BM_MveeFit)->Arg(24)->Arg(300)->Arg(3000);

void BM_TriangleTest(benchmark::State &state, double spread, bool coplanar)
{
    const auto pairs = randomPairs(4096, spread, coplanar);
    std::size_t i = 0, hits = 0;
    for (auto _ : state)
    {
        const auto &p = pairs[i & 4095];
        hits += trianglesIntersect(p.a[0], p.a[1], p.a[2], p.b[0], p.b[1], p.b[2]);
        ++i;
    }
    state.counters["hit fraction"] = double(hits) / double(i);
}
BENCHMARK_CAPTURE(BM_TriangleTest, generic_near, 1.0, false);
BENCHMARK_CAPTURE(BM_TriangleTest, generic_far, 3.0, false);
BENCHMARK_CAPTURE(BM_TriangleTest, coplanar, 1.0, true);

void BM_TriangleDistance(benchmark::State &state)
{
    const auto pairs = randomPairs(4096, 3.0, false);
    std::size_t i = 0;
    double sum = 0.0;
    for (auto _ : state)
    {
        const auto &p = pairs[i & 4095];
        sum += triangleDistance(p.a[0], p.a[1], p.a[2], p.b[0], p.b[1], p.b[2]);
        ++i;
    }
    benchmark::DoNotOptimize(sum);
}
BENCHMARK(BM_TriangleDistance);

void BM_Orient3d(benchmark::State &state, bool degenerate)
{
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vec3> pts(4096);
    for (auto &p : pts)
        p = Vec3(u(rng), u(rng), u(rng));
    std::size_t i = 0;
    int sum = 0;
    for (auto _ : state)
    {
        const Vec3 &a = pts[i & 4095], &b = pts[(i + 1) & 4095], &c = pts[(i + 2) & 4095];
        // The degenerate case puts d on the segment ab (up to the rounding of the midpoint), near the plane.
        const Vec3 d = degenerate ? Vec3(0.5 * (a + b)) : pts[(i + 3) & 4095];
        sum += orient3d(a, b, c, d);
        ++i;
    }
    benchmark::DoNotOptimize(sum);
}
BENCHMARK_CAPTURE(BM_Orient3d, generic, false);
BENCHMARK_CAPTURE(BM_Orient3d, on_plane_exact_fallback, true);

// Node-like volumes: each fitted to 24 points of a random flattened blob (extents 0.1..1, random
// orientation), the second of a pair centred within 2 of the first (overlap fractions printed).
template <class Volume>
std::vector<std::pair<Volume, Volume>> fittedPairs()
{
    std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.1, 1.0);
    const auto cloud = [&](const Vec3 &centre) {
        const Mat3 r = randomRotation();
        const Vec3 extents(e(rng), e(rng), e(rng));
        std::vector<Vec3> points(24);
        for (Vec3 &p : points)
            p = centre + r * Vec3(u(rng), u(rng), u(rng)).cwiseProduct(extents);
        return points;
    };
    std::vector<std::pair<Volume, Volume>> pairs(1024);
    for (auto &p : pairs)
    {
        p.first = VolumeTraits<Volume>::fit(cloud(Vec3::Zero()));
        p.second = VolumeTraits<Volume>::fit(cloud(2.0 * Vec3(u(rng), u(rng), u(rng))));
    }
    return pairs;
}

// One node-pair test as the trees run it: both volumes in the world frame.
template <class Volume>
void BM_VolumeOverlap(benchmark::State &state)
{
    const auto pairs = fittedPairs<Volume>();
    std::size_t i = 0, hits = 0;
    for (auto _ : state)
    {
        const auto &p = pairs[i & 1023];
        hits += VolumeTraits<Volume>::overlap(p.first, p.second, 1e-12);
        ++i;
    }
    state.counters["overlap fraction"] = double(hits) / double(i);
}

// Placing one robot node's volume in the world frame (once per node and query).
template <class Volume>
void BM_VolumeTransform(benchmark::State &state)
{
    const auto pairs = fittedPairs<Volume>();
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<RigidTransform> poses(1024);
    for (auto &pose : poses)
        pose = {randomRotation(), Vec3(u(rng), u(rng), u(rng))};
    std::size_t i = 0;
    // What a query works out once from its pose (k-DOPs: the rotation's mapping; others: the pose).
    using Placement = PlacementOf<Volume>;
    typename Placement::Type placement = Placement::of(poses[0]);
    for (auto _ : state)
    {
        // A new rotation every 64 nodes, as a query places tens of nodes by one pose; its set-up
        // is counted, shared by those 64.
        if ((i & 63) == 0)
            placement = Placement::of(poses[(i >> 6) & 1023]);
        benchmark::DoNotOptimize(VolumeTraits<Volume>::transformed(pairs[i & 1023].first, placement));
        ++i;
    }
}

#define HCD_VOLUME_BENCHMARKS(Volume, label)                                                                           \
    BENCHMARK_TEMPLATE(BM_VolumeOverlap, Volume)->Name("BM_VolumeOverlap/" label);                                     \
    BENCHMARK_TEMPLATE(BM_VolumeTransform, Volume)->Name("BM_VolumeTransform/" label);
HCD_VOLUME_BENCHMARKS(Obb, "obb")
HCD_VOLUME_BENCHMARKS(Ellipsoid, "ellipsoid")
HCD_VOLUME_BENCHMARKS(HybridVolume<false>, "hybrid")
HCD_VOLUME_BENCHMARKS(HybridVolume<true>, "hybrid-ellipsoid-first")
HCD_VOLUME_BENCHMARKS(Sphere, "sphere")
HCD_VOLUME_BENCHMARKS(Aabb, "aabb")
HCD_VOLUME_BENCHMARKS(FixedAabb, "aabb-fixed")
HCD_VOLUME_BENCHMARKS(KDop<14>, "kdop14")
HCD_VOLUME_BENCHMARKS(KDop<18>, "kdop18")
HCD_VOLUME_BENCHMARKS(KDop<26>, "kdop26")
HCD_VOLUME_BENCHMARKS(Ssv, "ssv")

// The octree checker's node test: a robot OBB against an axis-aligned cell (a cube as big as the
// second blob's box); placing a robot node is the OBB's.
void BM_VolumeOverlapOctreeCell(benchmark::State &state)
{
    const auto pairs = fittedPairs<Obb>();
    std::vector<Obb> cells;
    for (const auto &p : pairs)
        cells.push_back({p.second.center, Mat3::Identity(), Vec3::Constant(p.second.halfExtents.maxCoeff())});
    std::size_t i = 0, hits = 0;
    for (auto _ : state)
    {
        hits += obbsOverlap(pairs[i & 1023].first, cells[i & 1023], 1e-12);
        ++i;
    }
    state.counters["overlap fraction"] = double(hits) / double(i);
}
BENCHMARK(BM_VolumeOverlapOctreeCell)->Name("BM_VolumeOverlap/octree");
BENCHMARK_TEMPLATE(BM_VolumeTransform, Obb)->Name("BM_VolumeTransform/octree");
HCD_VOLUME_BENCHMARKS(MedialSphere, "medial")
HCD_VOLUME_BENCHMARKS(CTreeVolume, "ctree")
}  // namespace
