// SPDX-License-Identifier: BSD-3-Clause
// Per-check comparison: the same random states (fixed seed, uniform in the problem's state space,
// as a sampling planner draws them) through every checker. Reports the median and mean time per
// check, the fraction in collision, and disagreements with `bruteforce`, as a Markdown table.
// With --distance, times distance() instead (FCL: fcl::distance) and counts the states where a
// checker's distance differs from the first listed checker's by more than 1e-9 relative (0 and
// positive answers differ when the robot is inside a closed obstacle, which FCL calls free).
// Each check is timed alone (two clock reads); the clock's own cost, measured before the table
// (`clockOverheadNs`), is subtracted from every time, since at ~100 ns per check it would
// otherwise be a third of what is compared. The last column gives the ratio with the clock's cost
// left in; --raw-times leaves it in everywhere.
//
//   hybridcd_bench_checkers [--states N] [--seed S] [--checker obb,fcl,...] [--no-reference] [--distance]
//   PROBLEM.cfg...
//   (--help lists the options and the checkers)
#include "bench_support.h"

#include "hybridcd/fcl/fcl_checker.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/query/checker_catalogue.h"

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
int run(const cli::CommandLine &cl, const CheckerCatalogue &checkers);
}  // namespace

int main(int argc, char **argv)
{
    const CheckerCatalogue checkers = checkersWithFcl();
    CLI::App app("Time per collision check of each checker on the same uniform random states, as a Markdown table.",
                 "hybridcd_bench_checkers");
    cli::configureApp(app);
    cli::CommandLine cl(app);
    cl.positionals("PROBLEM.cfg", "the problems, one table row per problem and checker")
        .option("states", "N", "random states per problem (default 20000)")
        .option("seed", "N", "seed of OMPL's random numbers (default 1)")
        .option("checker", "NAME[,NAME...]", "the checkers (default obb,fcl)")
        .flag("no-reference", "skip the brute-force reference (no disagreement count)")
        .flag("distance", "time distance() (FCL: fcl::distance) instead of collision checks")
        .flag("no-grid", "hybridcd checkers without their clearance grid first layer")
        .flag("raw-times", "leave the clock's own cost (two reads per check) in every time")
        .footer("\nExample:\n  hybridcd_bench_checkers --states 5000 --checker obb,lp,fcl problems/window_3d.cfg\n\n" +
                cli::checkerHelp(checkers));
    return bench::runProgram(app, cl, argc, argv, [&] { return run(cl, checkers); });
}

namespace
{
int run(const cli::CommandLine &cl, const CheckerCatalogue &checkers)
{
    const std::size_t stateCount = std::size_t(cl.positiveInteger("states", 20000));
    const std::uint_fast32_t seed = cl.has("seed") ? cli::seedOf(cl) : 1;
    const std::vector<std::string> names = cli::checkerNamesOf(cl, checkers, {}, "obb,fcl");
    const bool distance = cl.has("distance");
    // Brute-force distance is quadratic: with --distance, checkers are compared with the first instead.
    const bool reference = !cl.has("no-reference") && !distance;
    const std::vector<std::string> &problems = cl.positionals();
    if (problems.empty())
        throw cli::UsageError("missing the problem files (.cfg)");
    ompl::RNG::setSeed(seed);
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

    const double clockNs = cl.has("raw-times") ? 0.0 : bench::clockOverheadNs();
    std::cout << "| problem | checker | median ns/" << (distance ? "distance" : "check") << " | mean ns/"
              << (distance ? "distance" : "check") << " | median vs fcl | in collision | "
              << (distance ? "differences from " + (names.empty() ? std::string("-") : names.front())
                           : std::string("disagreements with bruteforce"))
              << " | build ms | volume tests/" << (distance ? "distance" : "check") << " | triangle tests/"
              << (distance ? "distance" : "check") << " | median vs fcl, clock's cost included |\n"
              << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const std::string &cfg : problems)
    {
        const LoadedProblem problem = loadProblem(cfg);
        const std::vector<RigidTransform> poses = bench::uniformPoses(problem, stateCount);

        std::vector<char> truth;
        if (reference)
        {
            const auto bf = checkers.make("bruteforce", problem.scene);
            for (const RigidTransform &p : poses)
                truth.push_back(bf->collides(p));
        }
        std::map<std::string, double> medians, rawMedians;
        std::vector<std::string> rows;
        std::vector<double> firstDistances;
        for (const std::string &name : names)
        {
            const auto buildStart = std::chrono::steady_clock::now();
            CheckerOptions options;
            options.clearanceGrid = !cl.has("no-grid");
            const auto checker = checkers.make(name, problem.scene, options);
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
            rawMedians[name] = median(ns);
            for (double &v : ns)
                v = std::max(0.0, v - clockNs);
            medians[name] = median(ns);
            std::ostringstream row;
            row << std::fixed << std::setprecision(0) << "| " << problem.config.name << " | " << name << " | "
                << medians[name] << " | " << mean << " | %RATIO% | " << std::setprecision(1)
                << 100.0 * double(colliding) / double(poses.size()) << "% | "
                << (reference || distance ? std::to_string(disagreements) : std::string("-")) << " | "
                << std::setprecision(1) << buildMs << " | " << std::setprecision(0)
                << double(context.stats.boundingVolumeTests) / double(poses.size()) << " | "
                << (name == "fcl"
                        ? std::string("-")  // FCL's own tests are not counted
                        : std::to_string(std::llround(double(context.stats.primitiveTests) / double(poses.size()))))
                << " | %RAWRATIO% |";
            rows.push_back(row.str());
        }
        std::size_t r = 0;
        for (const std::string &name : names)
        {
            std::string row = rows[r++];
            const auto ratioTo = [&](const std::map<std::string, double> &m) {
                std::ostringstream ratio;
                if (m.count("fcl"))
                    ratio << std::fixed << std::setprecision(2) << m.at(name) / m.at("fcl");
                else
                    ratio << "-";
                return ratio.str();
            };
            row.replace(row.find("%RATIO%"), 7, ratioTo(medians));
            row.replace(row.find("%RAWRATIO%"), 10, ratioTo(rawMedians));
            std::cout << row << '\n' << std::flush;
        }
    }
    std::cout << "\nTimes are net of the clock's own cost, " << std::fixed << std::setprecision(1) << clockNs
              << " ns per timed check (median of back-to-back steady_clock reads).\n";
    return 0;
}
}  // namespace
