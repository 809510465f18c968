// SPDX-License-Identifier: BSD-3-Clause
// Per-check comparison: the same random states (fixed seed, uniform in the problem's state space,
// as a sampling planner draws them) through every checker. Reports the median and mean time per
// check, the fraction in collision, and disagreements with `bruteforce`, as a Markdown table.
// With --distance, times distance() instead (FCL: fcl::distance) and counts the states where a
// checker's distance differs from the first listed checker's by more than 1e-9 relative (0 and
// positive answers differ when the robot is inside a closed obstacle, which FCL calls free).
//
//   hybridcd_bench_checkers [--states N] [--seed S] [--checker obb,fcl,...] [--no-reference] [--distance] PROBLEM.cfg...
#include "bench_support.h"

#include "hybridcd/fcl/fcl_checker.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/query/checker_registry.h"

#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

using namespace hcd;
using hcd::bench::median;

namespace
{

std::vector<std::string> split(const std::string &s)
{
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ','))
        out.push_back(item);
    return out;
}
}  // namespace

int main(int argc, char **argv)
{
    std::size_t stateCount = 20000;
    std::uint_fast32_t seed = 1;
    std::string checkers = "obb,fcl";
    bool reference = true;
    bool distance = false;
    std::vector<std::string> problems;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        if (a == "--states" && i + 1 < argc)
            stateCount = std::stoul(argv[++i]);
        else if (a == "--seed" && i + 1 < argc)
            seed = std::uint_fast32_t(std::stoul(argv[++i]));
        else if (a == "--checker" && i + 1 < argc)
            checkers = argv[++i];
        else if (a == "--no-reference")
            reference = false;
        else if (a == "--distance")
            distance = true;
        else if (a.rfind("--", 0) == 0)
        {
            std::cerr << "usage: " << argv[0]
                      << " [--states N] [--seed S] [--checker a,b,...] [--no-reference] [--distance] PROBLEM.cfg...\n";
            return 1;
        }
        else
            problems.push_back(a);
    }
    registerFclChecker();
    ompl::RNG::setSeed(seed);
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

    const std::vector<std::string> names = split(checkers);
    if (distance)
        reference = false;  // brute-force distance is quadratic; checkers are compared with the first instead
    std::cout << "| problem | checker | median ns/" << (distance ? "distance" : "check") << " | mean ns/"
              << (distance ? "distance" : "check") << " | median vs fcl | in collision | "
              << (distance ? "differences from " + (names.empty() ? std::string("-") : names.front())
                           : std::string("disagreements with bruteforce"))
              << " | build ms | volume tests/" << (distance ? "distance" : "check") << " |\n"
              << "|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const std::string &cfg : problems)
    {
        const LoadedProblem problem = loadProblem(cfg);
        const std::vector<RigidTransform> poses = bench::uniformPoses(problem, stateCount);

        std::vector<char> truth;
        if (reference)
        {
            const auto bf = makeChecker("bruteforce", problem.scene);
            for (const RigidTransform &p : poses)
                truth.push_back(bf->collides(p));
        }
        std::map<std::string, double> medians;
        std::vector<std::string> rows;
        std::vector<double> firstDistances;
        for (const std::string &name : names)
        {
            const auto buildStart = std::chrono::steady_clock::now();
            const auto checker = makeChecker(name, problem.scene);
            const double buildMs =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - buildStart).count();
            std::vector<double> ns(poses.size());
            std::size_t colliding = 0, disagreements = 0;
            QueryContext context;  // one per stream of queries, as the OMPL adapter keeps one per thread
            std::vector<double> distances;
            for (std::size_t i = 0; i < poses.size(); ++i)
            {
                const auto t0 = std::chrono::steady_clock::now();
                bool hit = false;
                if (distance)
                {
                    const double d = checker->distance(poses[i], context);
                    ns[i] = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
                    hit = !(d > 0.0);
                    distances.push_back(d);
                    if (!firstDistances.empty())
                    {
                        const double r = firstDistances[i];
                        disagreements += std::abs(d - r) > 1e-9 * std::max(1.0, std::abs(r)) ? 1 : 0;
                    }
                }
                else
                {
                    hit = checker->collides(poses[i], context);
                    ns[i] = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
                    if (reference && bool(truth[i]) != hit)
                        ++disagreements;
                }
                colliding += hit;
            }
            if (distance && firstDistances.empty())
                firstDistances = distances;
            double mean = 0.0;
            for (double v : ns)
                mean += v / double(ns.size());
            medians[name] = median(ns);
            std::ostringstream row;
            row << std::fixed << std::setprecision(0) << "| " << problem.config.name << " | " << name << " | "
                << medians[name] << " | " << mean << " | %RATIO% | " << std::setprecision(1)
                << 100.0 * double(colliding) / double(poses.size()) << "% | "
                << (reference || distance ? std::to_string(disagreements) : std::string("-")) << " | " << std::setprecision(1)
                << buildMs << " | " << std::setprecision(0) << double(context.stats.boundingVolumeTests) / double(poses.size())
                << " |";
            rows.push_back(row.str());
        }
        std::size_t r = 0;
        for (const std::string &name : names)
        {
            std::string row = rows[r++];
            std::ostringstream ratio;
            if (medians.count("fcl"))
                ratio << std::fixed << std::setprecision(2) << medians[name] / medians["fcl"];
            else
                ratio << "-";
            row.replace(row.find("%RATIO%"), 7, ratio.str());
            std::cout << row << '\n' << std::flush;
        }
    }
    return 0;
}
