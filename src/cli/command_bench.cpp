// SPDX-License-Identifier: BSD-3-Clause
// `hybridcd bench`: OMPL benchmark runs of a problem's planners with one or more checkers, written
// as an OMPL benchmark log (readable by ompl_benchmark_statistics), optionally one shard of many.
#include "command_line.h"
#include "commands.h"
#include "problem_checks.h"

#include "hybridcd/io/atomic_file.h"
#include "hybridcd/io/input_error.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/planners/planner_catalogue.h"
#include "hybridcd/query/checker_catalogue.h"

#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/RandomNumbers.h>

#include <iostream>
#include <map>
#include <sstream>

namespace hcd::cli
{
namespace
{
// "I/N" with 0 <= I < N.
std::pair<unsigned, unsigned> parseShard(const std::string &text)
{
    const auto slash = text.find('/');
    try
    {
        if (slash != std::string::npos)
        {
            const long index = std::stol(text.substr(0, slash)), count = std::stol(text.substr(slash + 1));
            if (count >= 1 && index >= 0 && index < count)
                return {unsigned(index), unsigned(count)};
        }
    }
    catch (const std::exception &)
    {
    }
    throw UsageError("--shard expects I/N with 0 <= I < N, got '" + text + "'");
}

struct CheckerSlot
{
    std::string name;
    std::shared_ptr<const CollisionChecker> checker;
    std::shared_ptr<StateValidityChecker> validity;
};
}  // namespace

void declareBench(CommandLine &cl)
{
    cl.positionals("PROBLEM.cfg", "the problem (OMPL.app's .cfg format); its [benchmark] section gives the defaults")
        .option("planner", "NAME[,NAME...]", "the planners (default: the .cfg's, else rrtconnect)")
        .option("runs", "N", "runs per planner and checker (default: the .cfg's run_count)")
        .option("time", "SECONDS", "time limit per run (default: the .cfg's time_limit)")
        .option("memory", "MB", "memory limit per run (default: the .cfg's mem_limit)")
        .option("shard", "I/N", "do only the runs whose index is I modulo N (0 <= I < N)")
        .option("out", "FILE.log", "the benchmark log (default NAME.log, or NAME.shardI.log)")
        .option("motion", "continuous|discrete", "how motions are checked (default continuous)")
        .option("seed", "N", "seed OMPL's random numbers (1 to 4294967295)");
    addCheckerOptions(cl, true);
    cl.footer(R"(
Writes an OMPL benchmark log, readable by ompl_benchmark_statistics.
Examples:
  hybridcd bench problems/window_3d.cfg --checker obb,fcl --runs 20 --time 10
  hybridcd bench problems/window_3d.cfg --runs 100 --shard 0/4 --out window.shard0.log
)");
}

int runBench(const CommandLine &cl, const CheckerCatalogue &checkers)
{
    if (cl.has("seed"))
        ompl::RNG::setSeed(seedOf(cl));
    const MotionCheck motion = parseMotionCheck(cl.text("motion", "continuous"));
    const auto [shardIndex, shardCount] = parseShard(cl.text("shard", "0/1"));
    const CheckerOptions checkerOptions = checkerOptionsOf(cl);
    const std::vector<std::string> checkerNames = checkerNamesOf(cl, checkers, checkerOptions);
    const LoadedProblem problem = loadProblemFor(cl);
    const ProblemConfig &cfg = problem.config;
    if (!cfg.control.empty())
        throw InputError(cfg.path, cfg.controlLine,
                         "control = " + cfg.control +
                             ": `bench` runs geometric planners only; plan this kinodynamic problem with `hybridcd "
                             "solve` (bench/README.md has its measurements)");

    const long long totalRuns = cl.positiveInteger("runs", cfg.benchmark.runCount);
    // Shard I of N does the runs whose index is I modulo N, so shards never overlap and together
    // make exactly the whole benchmark.
    const unsigned shardRuns = unsigned((totalRuns - shardIndex + shardCount - 1) / shardCount);
    const double timeLimit = cl.positiveNumber("time", cfg.benchmark.timeLimit);
    const double memoryLimit = cl.positiveNumber("memory", cfg.benchmark.memoryLimit);
    if (shardRuns == 0)
        throw UsageError("shard " + std::to_string(shardIndex) + "/" + std::to_string(shardCount) + " has no runs of " +
                         std::to_string(totalRuns));
    // A benchmark may run for hours: an unwritable log or an impossible start must fail now.
    const std::string out =
        cl.text("out", cfg.name + (shardCount > 1 ? ".shard" + std::to_string(shardIndex) : "") + ".log");
    checkOutputPath(out, cl.has("out") ? "--out" : "the default output", inputFilesOf(problem));
    requireStartAndGoalInVolume(cfg);

    std::vector<PlannerRequest> requests;
    if (cl.has("planner"))
        for (const std::string &p : splitList(cl.text("planner", "")))
            requests.push_back({p, "", {}});
    else
        requests = cfg.planners;
    if (requests.empty())
        requests.push_back({"rrtconnect", "", {}});

    std::vector<CheckerSlot> slots;
    for (const std::string &name : checkerNames)
        slots.push_back({name, checkers.make(name, problem.scene, checkerOptions), nullptr});

    PlanningProblem planning = makePlanningProblem(problem, slots.front().checker, motion);
    requireCollisionFreeStartAndGoal(problem, planning);
    for (CheckerSlot &slot : slots)
        slot.validity = installChecker(planning, problem, slot.checker, motion);

    ompl::tools::Benchmark benchmark(*planning.setup, cfg.name);
    std::map<const ompl::base::Planner *, std::size_t> slotOf;
    for (std::size_t c = 0; c < slots.size(); ++c)
        for (const PlannerRequest &request : requests)
        {
            ompl::base::PlannerPtr planner = makePlanner(request, planning.setup->getSpaceInformation());
            // The checker (and continuous motion checking) in the name keeps configurations apart when
            // several logs are merged into one database.
            planner->setName(planner->getName() + "[" + slots[c].name +
                             (motion == MotionCheck::Continuous ? "+ccd" : "") + "]");
            slotOf[planner.get()] = c;
            benchmark.addPlanner(planner);
        }
    benchmark.addExperimentParameter("checkers", "VARCHAR(256)", cl.text("checker", "obb"));
    benchmark.addExperimentParameter("motion_check", "VARCHAR(32)", cl.text("motion", "continuous"));
    benchmark.addExperimentParameter("shard_index", "INTEGER", std::to_string(shardIndex));
    benchmark.addExperimentParameter("shard_count", "INTEGER", std::to_string(shardCount));
    benchmark.addExperimentParameter("total_runs", "INTEGER", std::to_string(totalRuns));

    const std::size_t totalThisShard = std::size_t(shardRuns) * slotOf.size();
    std::size_t done = 0;
    std::map<const ompl::base::Planner *, unsigned> runsSoFar;
    benchmark.setPreRunEvent([&](const ompl::base::PlannerPtr &planner) {
        // Point the space at this planner's checker and zero its counters.
        const CheckerSlot &slot = slots[slotOf.at(planner.get())];
        installChecker(planning, problem, slot.checker, motion)->resetCounters();
        slots[slotOf.at(planner.get())].validity = planning.validity;
    });
    benchmark.setPostRunEvent([&](const ompl::base::PlannerPtr &planner, ompl::tools::Benchmark::RunProperties &run) {
        const CheckerSlot &slot = slots[slotOf.at(planner.get())];
        const unsigned local = runsSoFar[planner.get()]++;
        run["collision checks INTEGER"] = std::to_string(slot.validity->checkCount());
        run["collision checking time REAL"] = std::to_string(slot.validity->checkSeconds());
        run["checker VARCHAR(32)"] = slot.name;
        run["run index INTEGER"] = std::to_string(shardIndex + std::size_t(local) * shardCount);
        ++done;
        std::cerr << "\r[" << done << "/" << totalThisShard << "] " << planner->getName() << " run " << local + 1 << "/"
                  << shardRuns << "   " << std::flush;
    });

    ompl::tools::Benchmark::Request request(timeLimit, memoryLimit, shardRuns, 0.05, false, false, true);
    benchmark.benchmark(request);
    std::cerr << '\n';

    AtomicFile log(out);
    if (!benchmark.saveResultsToStream(log.stream()))
        throw InputError(out, 0, "cannot write the benchmark log");
    log.commit();
    std::cout << "benchmark log written to: " << out << " (" << slotOf.size() << " planner/checker pairs, " << shardRuns
              << " runs each)\n";
    return kSuccess;
}
}  // namespace hcd::cli
