// SPDX-License-Identifier: BSD-3-Clause
// Time per exact point-in-solid query (the containment test of solid semantics) on OMPL.app's
// largest environments, at uniform points in the environment's bounding box.
//
//   HYBRIDCD_OMPLAPP_RESOURCES=../shared/omplapp-resources build/bench/hybridcd_bench_solid_micro
#include "hybridcd/geometry/solid_components.h"
#include "hybridcd/io/mesh_loader.h"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <random>

using namespace hcd;

namespace
{
std::string resource(const std::string &relative)
{
    const char *env = std::getenv("HYBRIDCD_OMPLAPP_RESOURCES");
    return std::string(env && *env ? env : HYBRIDCD_DEFAULT_OMPLAPP_RESOURCES) + "/" + relative;
}

void insideAnySolid(benchmark::State &state, const std::string &relative)
{
    const std::string path = resource(relative);
    if (!std::filesystem::exists(path))
    {
        state.SkipWithError(("missing " + path + "; set HYBRIDCD_OMPLAPP_RESOURCES").c_str());
        return;
    }
    const std::shared_ptr<const TriangleMesh> mesh = loadMesh(path, MeshRole::Environment).mesh;
    const SolidQuery query(mesh);
    const BoundingBox box = mesh->bounds();
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec3> points(1 << 16);
    for (Vec3 &p : points)
        p = box.min + (box.max - box.min).cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    std::size_t i = 0, inside = 0;
    for (auto _ : state)
    {
        const bool in = query.insideAnySolid(points[i++ & (points.size() - 1)]);
        inside += in ? 1 : 0;
        benchmark::DoNotOptimize(in);
    }
    state.counters["inside_fraction"] = double(inside) / double(state.iterations());
}
}  // namespace

BENCHMARK_CAPTURE(insideAnySolid, Home, std::string("3D/Home_env.dae"));
BENCHMARK_CAPTURE(insideAnySolid, Abstract, std::string("3D/Abstract_env.dae"));
