// SPDX-License-Identifier: BSD-3-Clause
// Broad phases on N coherently moving boxes (N = 100, 1000, 10000): the time of one step, that is
// moving every box and then listing every overlapping pair, for hybridcd's sweep and prune (all
// boxes in one updateMany, and one update per box), its brute-force reference, and FCL 0.7's
// DynamicAABBTreeCollisionManager and SaPCollisionManager (fcl::Box objects whose translations are set, AABBs
// recomputed, manager updated, then collide() with a callback that only records the pair, so no narrow phase is timed).
//
// Scene: boxes with half extents uniform in [0.2, 0.6] in a cube whose side grows as N^(1/3)
// (about one overlap per box), each moving at a constant velocity of at most 0.02 per step and
// bouncing off the cube's walls; in a second run 1% of the boxes also jump to a random place each
// step. Every method sees the same motion. Prints the median nanoseconds per step over the steps, the pairs
// found at the last step (which must be equal) and each method's ratio to the sweep and prune.
//
//   g++ -O2 ... bench/micro/broad_phase_micro.cpp ... -lfcl -lccd && ./broad_phase_micro
#include "hybridcd/broadphase/brute_force_broad_phase.h"
#include "hybridcd/broadphase/sweep_and_prune.h"

#include <fcl/broadphase/broadphase_SaP.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <type_traits>
#include <vector>

using namespace hcd;

namespace
{
struct Scene
{
    std::vector<Vec3> position, half, velocity;
    double side = 0.0;
    double jumps = 0.0;  // fraction of the boxes that jump each step
    std::mt19937_64 rng;

    Scene(int n, double jumpFraction, std::uint64_t seed) : jumps(jumpFraction), rng(seed)
    {
        side = 2.0 * std::cbrt(double(n));
        std::uniform_real_distribution<double> where(0.0, side), size(0.2, 0.6), speed(-0.02, 0.02);
        for (int i = 0; i < n; ++i)
        {
            position.emplace_back(where(rng), where(rng), where(rng));
            half.emplace_back(size(rng), size(rng), size(rng));
            velocity.emplace_back(speed(rng), speed(rng), speed(rng));
        }
    }

    void step()
    {
        std::uniform_real_distribution<double> u(0.0, 1.0), where(0.0, side);
        for (std::size_t i = 0; i < position.size(); ++i)
        {
            if (u(rng) < jumps)
            {
                position[i] = Vec3(where(rng), where(rng), where(rng));
                continue;
            }
            position[i] += velocity[i];
            for (int k = 0; k < 3; ++k)
                if (position[i][k] < 0.0 || position[i][k] > side)
                    velocity[i][k] = -velocity[i][k];
        }
    }

    BroadPhaseBox box(std::size_t i) const { return {position[i] - half[i], position[i] + half[i]}; }
};

double median(std::vector<double> v)
{
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    return v[v.size() / 2];
}

using Clock = std::chrono::steady_clock;

struct Measured
{
    double medianNs = 0.0;
    std::size_t pairs = 0;
    double swapsPerStep = 0.0;  // endpoint swaps (sweep and prune only)
};

template <typename Phase, bool Batch = false>
Measured runHybridcd(int n, double jumps, int steps)
{
    Scene scene(n, jumps, 7);
    Phase phase;
    std::vector<BodyHandle> handles;
    for (int i = 0; i < n; ++i)
        handles.push_back(phase.add(scene.box(std::size_t(i)), std::uint32_t(i)));
    std::vector<UserDataPair> pairs;
    std::vector<BroadPhaseBox> boxes(static_cast<std::size_t>(n));
    phase.overlappingPairs(pairs);
    if constexpr (std::is_same_v<Phase, SweepAndPrune>)
        phase.resetSwaps();
    std::vector<double> ns;
    for (int s = 0; s < steps; ++s)
    {
        scene.step();
        const auto t0 = Clock::now();
        if constexpr (Batch)
        {
            for (int i = 0; i < n; ++i)
                boxes[std::size_t(i)] = scene.box(std::size_t(i));
            phase.updateMany(handles.data(), boxes.data(), handles.size());
        }
        else
        {
            for (int i = 0; i < n; ++i)
                phase.update(handles[std::size_t(i)], scene.box(std::size_t(i)));
        }
        phase.overlappingPairs(pairs);
        ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count());
    }
    double swaps = 0.0;
    if constexpr (std::is_same_v<Phase, SweepAndPrune>)
        swaps = double(phase.swaps()) / double(steps);
    return {median(ns), pairs.size(), swaps};
}

struct PairRecorder
{
    std::vector<std::pair<std::uintptr_t, std::uintptr_t>> pairs;
};

bool recordPair(fcl::CollisionObjectd *a, fcl::CollisionObjectd *b, void *data)
{
    auto *recorder = static_cast<PairRecorder *>(data);
    recorder->pairs.emplace_back(reinterpret_cast<std::uintptr_t>(a->getUserData()),
                                 reinterpret_cast<std::uintptr_t>(b->getUserData()));
    return false;  // go on: every pair
}

template <typename Manager>
Measured runFcl(int n, double jumps, int steps)
{
    Scene scene(n, jumps, 7);
    std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
    std::vector<fcl::CollisionObjectd *> raw;
    for (int i = 0; i < n; ++i)
    {
        auto shape = std::make_shared<fcl::Boxd>(2.0 * scene.half[std::size_t(i)]);
        fcl::Transform3d pose = fcl::Transform3d::Identity();
        pose.translation() = scene.position[std::size_t(i)];
        objects.push_back(std::make_unique<fcl::CollisionObjectd>(shape, pose));
        objects.back()->setUserData(reinterpret_cast<void *>(std::uintptr_t(i)));
        objects.back()->computeAABB();
        raw.push_back(objects.back().get());
    }
    Manager manager;
    manager.registerObjects(raw);
    manager.setup();
    PairRecorder recorder;
    std::vector<double> ns;
    for (int s = 0; s < steps; ++s)
    {
        scene.step();
        const auto t0 = Clock::now();
        for (int i = 0; i < n; ++i)
        {
            objects[std::size_t(i)]->setTranslation(scene.position[std::size_t(i)]);
            objects[std::size_t(i)]->computeAABB();
        }
        manager.update();
        recorder.pairs.clear();
        manager.collide(&recorder, recordPair);
        ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count());
    }
    return {median(ns), recorder.pairs.size()};
}
}  // namespace

int main(int argc, char **argv)
{
    for (int i = 1; i < argc; ++i)
        if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0)
        {
            std::printf("usage: %s\n  times one step (move every box, list every overlapping pair) of the broad\n"
                        "  phases for N = 100, 1000, 10000 coherently moving boxes; no options.\n",
                        argv[0]);
            return 0;
        }
        else
        {
            std::fprintf(stderr, "%s: unknown option '%s' (see --help)\n", argv[0], argv[i]);
            return 1;
        }
    for (const double jumps : {0.0, 0.01})
    {
        std::printf("%s\n", jumps == 0.0 ? "coherent motion only" : "coherent motion, 1% of the boxes jump each step");
        std::printf("%-8s %-36s %14s %8s %8s %12s\n", "N", "method", "median ns/step", "pairs", "x SAP", "swaps/step");
        for (const int n : {100, 1000, 10000})
        {
            const int steps = n <= 100 ? 400 : n <= 1000 ? 100 : 30;
            const Measured sap = runHybridcd<SweepAndPrune, true>(n, jumps, steps);
            const Measured sapOneByOne = runHybridcd<SweepAndPrune>(n, jumps, steps);
            const Measured brute = runHybridcd<BruteForceBroadPhase>(n, jumps, steps);
            const Measured tree = runFcl<fcl::DynamicAABBTreeCollisionManagerd>(n, jumps, steps);
            const Measured fclSap = runFcl<fcl::SaPCollisionManagerd>(n, jumps, steps);
            const auto row = [&](const char *name, const Measured &m) {
                std::printf("%-8d %-36s %14.0f %8zu %8.2f %12.0f\n", n, name, m.medianNs, m.pairs,
                            m.medianNs / sap.medianNs, m.swapsPerStep);
            };
            row("hybridcd SweepAndPrune (updateMany)", sap);
            row("hybridcd SweepAndPrune (update each)", sapOneByOne);
            row("hybridcd BruteForceBroadPhase", brute);
            row("fcl DynamicAABBTreeCollisionManager", tree);
            row("fcl SaPCollisionManager", fclSap);
        }
    }
    return 0;
}
