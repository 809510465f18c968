// SPDX-License-Identifier: BSD-3-Clause
// Scaling: one scene with its meshes split into ever more triangles (each triangle into four, at
// edge midpoints, so the shape stays the same), reporting build time, memory and time per check
// for each checker side by side.
//
//   hybridcd_bench_scaling [--max-triangles N] [--states N] [--checker obb,fcl] PROBLEM.cfg
#include "bench_support.h"

#include "hybridcd/fcl/fcl_checker.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/query/checker_registry.h"

#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

using namespace hcd;
using hcd::bench::median;

namespace
{
TriangleMesh subdivide(const TriangleMesh &in)
{
    TriangleMesh out;
    out.vertices = in.vertices;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
        const auto key = std::minmax(a, b);
        auto it = midpoints.find(key);
        if (it != midpoints.end())
            return it->second;
        out.vertices.push_back(0.5 * (in.vertices[a] + in.vertices[b]));
        return midpoints[key] = std::uint32_t(out.vertices.size() - 1);
    };
    for (const auto &t : in.triangles)
    {
        const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
        out.triangles.push_back({t[0], ab, ca});
        out.triangles.push_back({ab, t[1], bc});
        out.triangles.push_back({ca, bc, t[2]});
        out.triangles.push_back({ab, bc, ca});
    }
    return out;
}

}  // namespace

int main(int argc, char **argv)
{
    std::size_t maxTriangles = 1100000, stateCount = 2000;
    std::string checkers = "obb,fcl", cfg;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        if (a == "--max-triangles" && i + 1 < argc)
            maxTriangles = std::stoul(argv[++i]);
        else if (a == "--states" && i + 1 < argc)
            stateCount = std::stoul(argv[++i]);
        else if (a == "--checker" && i + 1 < argc)
            checkers = argv[++i];
        else
            cfg = a;
    }
    if (cfg.empty())
    {
        std::cerr << "usage: " << argv[0] << " [--max-triangles N] [--states N] [--checker a,b] PROBLEM.cfg\n";
        return 1;
    }
    registerFclChecker();
    ompl::RNG::setSeed(1);
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

    LoadedProblem problem = loadProblem(cfg);
    const std::vector<RigidTransform> poses = bench::uniformPoses(problem, stateCount);

    std::cout << "| environment triangles | robot triangles | checker | build ms | memory MiB | median ns/check | "
                 "vs fcl |\n|---:|---:|---|---:|---:|---:|---:|\n";
    TriangleMesh env = *problem.world.mesh, robot = *problem.robot.mesh;
    while (env.triangleCount() < 900)
        env = subdivide(env);
    while (env.triangleCount() <= maxTriangles)
    {
        CollisionScene scene;
        scene.environment = std::make_shared<const TriangleMesh>(env);
        scene.robot = std::make_shared<const TriangleMesh>(robot);
        std::map<std::string, double> medians;
        std::vector<std::string> rows;
        std::stringstream names(checkers);
        std::string name;
        std::vector<std::string> order;
        while (std::getline(names, name, ','))
        {
            order.push_back(name);
            const auto t0 = std::chrono::steady_clock::now();
            const auto checker = makeChecker(name, scene);
            const double buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            std::size_t bytes = 0;
            for (const HierarchyReport &h : checker->hierarchies())
                bytes += h.memoryBytes;
            std::vector<double> ns;
            QueryContext context;
            for (const RigidTransform &p : poses)
            {
                const auto q0 = std::chrono::steady_clock::now();
                checker->collides(p, context);
                ns.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - q0).count());
            }
            medians[name] = median(ns);
            std::ostringstream row;
            row << std::fixed << std::setprecision(1) << "| " << env.triangleCount() << " | " << robot.triangleCount()
                << " | " << name << " | " << buildMs << " | " << double(bytes) / (1024.0 * 1024.0) << " | "
                << std::setprecision(0) << medians[name] << " | ";
            rows.push_back(row.str());
        }
        for (std::size_t i = 0; i < rows.size(); ++i)
        {
            std::cout << rows[i];
            if (medians.count("fcl"))
                std::cout << std::fixed << std::setprecision(2) << medians[order[i]] / medians["fcl"];
            std::cout << " |\n" << std::flush;
        }
        env = subdivide(env);
        if (robot.triangleCount() * 50 < env.triangleCount())
            robot = subdivide(robot);
    }
    return 0;
}
