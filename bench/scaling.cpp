// SPDX-License-Identifier: BSD-3-Clause
// Scaling: one scene with its meshes split into ever more triangles (each triangle into four, at
// edge midpoints, so the shape stays the same), reporting build time, memory and time per check
// for each checker side by side.
//
//   hybridcd_bench_scaling [--max-triangles N] [--states N] [--checker obb,fcl] PROBLEM.cfg
#include "bench_support.h"

#include "hybridcd/fcl/fcl_checker.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/query/checker_catalogue.h"

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

namespace
{
int run(const cli::CommandLine &cl, const CheckerCatalogue &checkers)
{
    const std::size_t maxTriangles = std::size_t(cl.positiveInteger("max-triangles", 1100000));
    const std::size_t stateCount = std::size_t(cl.positiveInteger("states", 2000));
    const std::vector<std::string> names = cli::checkerNamesOf(cl, checkers, {}, "obb,fcl");
    const std::string &cfg = cl.problem();
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
        std::vector<std::string> order;
        for (const std::string &name : names)
        {
            order.push_back(name);
            const auto t0 = std::chrono::steady_clock::now();
            CheckerOptions options;
            options.clearanceGrid = !cl.has("no-grid");
            const auto checker = checkers.make(name, scene, options);
            const double buildMs =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
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
}  // namespace

int main(int argc, char **argv)
{
    const CheckerCatalogue checkers = checkersWithFcl();
    CLI::App app("Build time, memory and time per check as the meshes are subdivided, per checker, as a Markdown "
                 "table.",
                 "hybridcd_bench_scaling");
    cli::configureApp(app);
    cli::CommandLine cl(app);
    cl.positionals("PROBLEM.cfg", "the problem whose meshes are subdivided")
        .option("max-triangles", "N", "stop above N environment triangles (default 1100000)")
        .option("states", "N", "random states per size (default 2000)")
        .flag("no-grid", "hybridcd checkers without their clearance grid first layer")
        .option("checker", "NAME[,NAME...]", "the checkers (default obb,fcl)")
        .footer(
            "\nExample:\n  hybridcd_bench_scaling --max-triangles 100000 --checker obb,fcl problems/window_3d.cfg\n\n" +
            cli::checkerHelp(checkers));
    return bench::runProgram(app, cl, argc, argv, [&] { return run(cl, checkers); });
}
