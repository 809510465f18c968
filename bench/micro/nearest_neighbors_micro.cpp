// SPDX-License-Identifier: BSD-3-Clause
// Nearest-neighbour search over poses: hcd::PoseNearestNeighbors against OMPL's
// NearestNeighborsGNATNoThreadSafety (what RRTConnect, RRT and PRM use by default), the same
// elements and queries, OMPL's own SE(2)/SE(3) distance. Reports time per nearest() and the
// distances measured per query.
//   build/bench/hybridcd_bench_nn_micro [--benchmark_filter=...]
// Elements: uniform poses in a cube of side 100, or "clustered": their positions squeezed into a
// tenth of it in x and y, as a planner's tree is where its free space is, while the queries (the
// planner's uniform samples) stay uniform over the whole cube.
#include "hybridcd/planners/pose_nearest_neighbors.h"

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/datastructures/NearestNeighborsGNATNoThreadSafety.h>
#include <ompl/util/RandomNumbers.h>

#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

namespace
{
namespace ob = ompl::base;

enum Structure
{
    kPoses,
    kGnat
};

struct Data
{
    ob::StateSpacePtr space;
    std::vector<ob::State *> elements, queries;
    ~Data()
    {
        for (auto *s : elements)
            space->freeState(s);
        for (auto *s : queries)
            space->freeState(s);
    }
};

void squeeze(ob::State *s, bool planar)
{
    if (planar)
    {
        auto *p = s->as<ob::SE2StateSpace::StateType>();
        p->setXY(0.1 * p->getX(), 0.1 * p->getY());
    }
    else
    {
        auto *p = s->as<ob::SE3StateSpace::StateType>();
        p->setXYZ(0.1 * p->getX(), 0.1 * p->getY(), p->getZ());
    }
}

// OMPL's SE(2) or SE(3) over the cube [-50, 50] of positions.
template <typename Space>
ob::StateSpacePtr poseSpace(unsigned dimensions)
{
    auto space = std::make_shared<Space>();
    ob::RealVectorBounds bounds(dimensions);
    bounds.setLow(-50);
    bounds.setHigh(50);
    space->setBounds(bounds);
    return space;
}

std::unique_ptr<Data> makeData(bool planar, bool clustered, std::size_t count)
{
    auto data = std::make_unique<Data>();
    data->space = planar ? poseSpace<ob::SE2StateSpace>(2) : poseSpace<ob::SE3StateSpace>(3);
    ompl::RNG::setSeed(7);
    auto sampler = data->space->allocDefaultStateSampler();
    for (std::size_t i = 0; i < count; ++i)
    {
        data->elements.push_back(data->space->allocState());
        sampler->sampleUniform(data->elements.back());
        if (clustered)
            squeeze(data->elements.back(), planar);
    }
    for (int i = 0; i < 1000; ++i)
    {
        data->queries.push_back(data->space->allocState());
        sampler->sampleUniform(data->queries.back());
    }
    return data;
}

void nearest(benchmark::State &state, Structure structure, bool planar, bool clustered)
{
    const auto data = makeData(planar, clustered, std::size_t(state.range(0)));
    std::shared_ptr<ompl::NearestNeighbors<ob::State *>> nn;
    if (structure == kPoses)
        nn = std::make_shared<hcd::PoseNearestNeighbors<ob::State *>>(
            *hcd::PoseMetric::of(*data->space), [](ob::State *const &s) -> const ob::State * { return s; });
    else
        nn = std::make_shared<ompl::NearestNeighborsGNATNoThreadSafety<ob::State *>>();
    std::size_t distances = 0;
    nn->setDistanceFunction([&](ob::State *const &a, ob::State *const &b) {
        ++distances;
        return data->space->distance(a, b);
    });
    for (auto *s : data->elements)
        nn->add(s);
    distances = 0;
    std::size_t queries = 0;
    for (auto _ : state)
    {
        benchmark::DoNotOptimize(nn->nearest(data->queries[queries % data->queries.size()]));
        ++queries;
    }
    state.counters["distances/query"] = double(distances) / double(queries);
}

void registerAll()
{
    for (const bool planar : {false, true})
        for (const bool clustered : {false, true})
            for (const Structure structure : {kPoses, kGnat})
            {
                const std::string name = std::string(structure == kPoses ? "PoseNearestNeighbors" : "GNAT") +
                                         (planar ? "/SE2" : "/SE3") + (clustered ? "/clustered" : "/uniform");
                benchmark::RegisterBenchmark(name.c_str(), nearest, structure, planar, clustered)
                    ->Arg(1000)
                    ->Arg(10000)
                    ->Arg(100000)
                    ->Unit(benchmark::kMicrosecond);
            }
}

const int registered = (registerAll(), 0);

}  // namespace
