// SPDX-License-Identifier: BSD-3-Clause
// What the benchmark programs share: the command line, medians, and the states a sampling planner
// would draw.
#pragma once

#include "command_line.h"

#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/query/checker_catalogue.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <functional>
#include <iostream>
#include <vector>

namespace hcd::bench
{
/// Parses argv into `app` (declared through `cl`), then runs `body`: --help and --version end
/// the run with 0, misuse (in parsing or a UsageError from `body`) with 1, other errors with 1.
inline int runProgram(CLI::App &app, const cli::CommandLine &cl, int argc, char **argv,
                      const std::function<int()> &body)
{
    if (const auto status = cli::parseArguments(app, argc, argv))
        return *status;
    try
    {
        return body();
    }
    catch (const cli::UsageError &e)
    {
        return cli::reportUsageError(cl, e.what());
    }
    catch (const std::exception &e)
    {
        std::cerr << app.get_name() << ": error: " << e.what() << '\n';
        return 1;
    }
}

/// Median of the values (the upper one of the middle pair for an even count).
inline double median(std::vector<double> values)
{
    std::nth_element(values.begin(), values.begin() + long(values.size() / 2), values.end());
    return values[values.size() / 2];
}

/// What timing an empty region costs: the median over `samples` back-to-back pairs of
/// steady_clock reads, in ns (the smallest of three such medians, so a burst of other load
/// does not inflate it). A check that takes 100 ns is timed as about 100 ns plus this; benches that
/// time single checks subtract it so that ratios compare the checks, not the clock.
inline double clockOverheadNs(std::size_t samples = 100000)
{
    double best = 0.0;
    std::vector<double> ns(samples);
    for (int round = 0; round < 3; ++round)
    {
        for (double &v : ns)
        {
            const auto t0 = std::chrono::steady_clock::now();
            v = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
        }
        const double m = median(ns);
        best = round == 0 ? m : std::min(best, m);
    }
    return best;
}

/// `count` poses uniform in the problem's state space (OMPL's sampler; seed it first with
/// ompl::RNG::setSeed for repeatable runs).
inline std::vector<RigidTransform> uniformPoses(const LoadedProblem &problem, std::size_t count)
{
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene), MotionCheck::Discrete);
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    auto sampler = si->allocStateSampler();
    ompl::base::State *s = si->allocState();
    std::vector<RigidTransform> poses;
    for (std::size_t i = 0; i < count; ++i)
    {
        sampler->sampleUniform(s);
        poses.push_back(poseOfState(s, problem.config.planar));
    }
    si->freeState(s);
    return poses;
}
}  // namespace hcd::bench
