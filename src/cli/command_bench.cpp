// SPDX-License-Identifier: BSD-3-Clause
// `hybridcd bench`: OMPL benchmark runs of a problem's planners with one or more checkers, written
// as an OMPL benchmark log (readable by ompl_benchmark_statistics), optionally one shard of many.
#include "command_line.h"
#include "command_scene.h"
#include "commands.h"
#include "planner_watchdog.h"
#include "problem_checks.h"

#include "hybridcd/io/atomic_file.h"
#include "hybridcd/io/input_error.h"
#include "hybridcd/ompl/control_problem.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/ompl/scene_planning.h"
#include "hybridcd/planners/planner_catalogue.h"
#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/scene/problem_bodies.h"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/RandomNumbers.h>

#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

namespace hcd::cli
{
namespace
{
// "I/N" with 0 <= I < N, two whole numbers and nothing else; N at most 2^32 - 1 (shards are
// counted in unsigned, and a shard's seed holds I in 32 bits).
std::pair<unsigned, unsigned> parseShard(const std::string &text)
{
    const auto slash = text.find('/');
    if (slash != std::string::npos)
    {
        const std::optional<long long> index = wholeNumber(text.substr(0, slash)),
                                       count = wholeNumber(text.substr(slash + 1));
        if (index && count && *index >= 0 && *index < *count)
        {
            if (*count > std::numeric_limits<unsigned>::max())
                throw UsageError("--shard expects I/N with N at most " +
                                 std::to_string(std::numeric_limits<unsigned>::max()) + ", got '" + text + "'");
            return {unsigned(*index), unsigned(*count)};
        }
    }
    throw UsageError("--shard expects I/N with 0 <= I < N, got '" + text + "'");
}

// The seed of shard I of N > 1: SplitMix64 of (base seed * 2^32 + I), folded into 1 .. 2^32 - 1
// (OMPL ignores a seed of 0). One shard (N = 1) keeps the base seed. bench/merge_shards.py
// recomputes it to check every shard it merges.
std::uint_fast32_t shardSeed(std::uint_fast32_t base, unsigned index, unsigned count)
{
    if (count == 1)
        return base;
    std::uint64_t z = ((std::uint64_t(base) << 32) | index) + 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return std::uint_fast32_t(z % 4294967295ULL) + 1;
}

// One compared configuration: a checker and how motions are checked, with its label.
struct CheckerSlot
{
    std::string checker;  // the catalogue name
    MotionCheck motion = MotionCheck::Continuous;
    CheckerOptions options;
    std::string label;  // "obb+continuous", "fcl+discrete(0.01)": unique within a benchmark
    std::shared_ptr<const CollisionChecker> instance;
    std::shared_ptr<StateValidityChecker> validity;
    std::shared_ptr<const Scene> scene;  ///< scene problems: the scene checked with `checker`
    /// OMPL.app's own set-up (FCL, OMPL's discrete motion checks): planned with OMPL's default
    /// nearest-neighbour structure, as OMPL.app plans, whatever --neighbors says.
    bool omplAppSetup = false;
};

// OMPL's default validity-checking resolution (a fraction of the state space's extent), which
// OMPL.app leaves unchanged: every configuration of a benchmark runs at it, set explicitly.
constexpr double kResolution = 0.01;

std::string shortNumber(double value)
{
    std::ostringstream s;
    s << value;
    return s.str();
}

// What "discrete" means in a label: OMPL's validity-checking resolution for geometric problems
// ("discrete(0.01)"), the propagation step in seconds for kinodynamic ones ("discrete(0.2s)": states
// checked at the ends of propagation steps only, as OMPL.app does).
std::string discreteLabel(bool kinodynamic)
{
    return kinodynamic ? "discrete(" + shortNumber(ControlSettings{}.propagationStep) + "s)"
                       : "discrete(" + shortNumber(kResolution) + ")";
}

// The configuration's name in the log: the checker, its options when they change its answers, and
// the motion check with its resolution, so that merged logs never mix two set-ups under one name.
std::string labelOf(const CheckerEntry &entry, const CheckerOptions &options, MotionCheck motion, bool kinodynamic)
{
    std::string label = entry.name;
    if (!entry.keepsOwnSemantics && options.semantics == ContactSemantics::SurfaceOnly)
        label += "-surface";
    if (options.approximateTolerance)
        label += "-approx(" + shortNumber(*options.approximateTolerance) + ")";
    return label + (motion == MotionCheck::Continuous ? "+continuous" : "+" + discreteLabel(kinodynamic));
}

std::vector<MotionCheck> motionsOf(const CommandLine &cl)
{
    std::vector<MotionCheck> motions;
    for (const std::string &name : splitList(cl.text("motion", "continuous")))
        try
        {
            motions.push_back(parseMotionCheck(name));
        }
        catch (const std::invalid_argument &)
        {
            throw UsageError("option --motion expects continuous, discrete or both (comma-separated), got '" + name +
                             "'");
        }
    if (motions.empty())
        throw UsageError("option --motion needs continuous, discrete or both");
    return motions;
}

// The checker/motion pairs to compare: every --checker with every --motion, then OMPL.app's own
// set-up (FCL state checks, OMPL's DiscreteMotionValidator; for kinodynamic problems, checks at the
// propagation steps only) unless --baseline none or already listed.
std::vector<CheckerSlot> configurationsOf(const CommandLine &cl, const CheckerCatalogue &checkers, bool kinodynamic,
                                          bool scene)
{
    const CheckerOptions options = checkerOptionsOf(cl);
    const std::vector<std::string> names = checkerNamesOf(cl, checkers, options);
    const std::vector<MotionCheck> motions = motionsOf(cl);
    // OMPL.app has no scenes of several robots: there is no set-up of its to compare with.
    const std::string baseline = cl.text("baseline", scene ? "none" : "omplapp");
    if (baseline != "omplapp" && baseline != "none")
        throw UsageError("option --baseline expects omplapp or none, got '" + baseline + "'");
    if (scene && baseline == "omplapp")
        throw UsageError("--baseline omplapp is OMPL.app's set-up of one robot; a scene problem (robot.K, "
                         "obstacle.K) has none: compare --checker NAME,... and --motion continuous,discrete");

    std::vector<CheckerSlot> slots;
    for (const std::string &name : names)
        for (const MotionCheck motion : motions)
        {
            const std::string label = labelOf(*checkers.find(name), options, motion, kinodynamic);
            for (const CheckerSlot &s : slots)
                if (s.label == label)
                    throw UsageError("the configuration " + label + " is given twice");
            slots.push_back({name, motion, options, label, nullptr, nullptr, nullptr});
        }
    // OMPL.app's set-up, fcl+discrete, whether listed or added as the baseline.
    const CheckerEntry *fcl = checkers.find("fcl");
    const std::string omplAppLabel = fcl ? labelOf(*fcl, {}, MotionCheck::Discrete, kinodynamic) : std::string();
    if (baseline == "omplapp")
    {
        if (!fcl)
            throw UsageError("--baseline omplapp needs the fcl checker, which this build lacks; use --baseline none");
        bool listed = false;
        for (const CheckerSlot &s : slots)
            listed = listed || s.label == omplAppLabel;
        if (!listed)
            slots.push_back({"fcl", MotionCheck::Discrete, {}, omplAppLabel, nullptr, nullptr, nullptr});
    }
    for (CheckerSlot &s : slots)
        s.omplAppSetup = fcl && s.label == omplAppLabel;
    return slots;
}

// A benchmark's experiments are told apart by their planners' names: two planners of one name
// would be merged by ompl_benchmark_statistics, as two configurations of one name would (refused
// by configurationsOf). `planners` are one configuration's, from --planner or the .cfg's [planner].
void requireDistinctPlannerNames(const std::vector<ompl::base::PlannerPtr> &planners, const CommandLine &cl,
                                 const ProblemConfig &cfg)
{
    for (std::size_t i = 0; i < planners.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (planners[i]->getName() == planners[j]->getName())
            {
                if (cl.has("planner"))
                    throw UsageError("option --planner gives the planner " + planners[i]->getName() + " twice, got '" +
                                     cl.text("planner", "") + "'");
                throw InputError(cfg.path, 0,
                                 "[planner] declares two planners named " + planners[i]->getName() +
                                     "; give one another name with TYPE.name = NAME");
            }
}

struct SceneBenchRun
{
    double timeLimit, memoryLimit;
    unsigned shardRuns, shardIndex, shardCount;
    long long totalRuns;
    bool seeded;
    std::uint_fast32_t baseSeed, seed;
    std::string out;
};

// A scene problem: every robot at once on the compound space; each configuration a scene whose
// mesh pairs use its checker, with continuous (SceneMotionValidator) or discrete motion checks.
int benchScene(const CommandLine &cl, const LoadedProblem &problem, std::vector<CheckerSlot> &slots,
               const std::vector<PlannerRequest> &requests, const SceneBenchRun &run)
{
    const ProblemConfig &cfg = problem.config;
    for (CheckerSlot &slot : slots)
    {
        slot.scene = makeProblemScene(problem, sceneOptionsOf(slot.checker, slot.options));
        requireFreeEnds(problem, *slot.scene);
    }
    ScenePlanningProblem planning = makeScenePlanningProblem(problem, slots.front().scene);
    const ompl::base::SpaceInformationPtr si = planning.setup->getSpaceInformation();
    si->setStateValidityCheckingResolution(kResolution);
    std::vector<std::shared_ptr<SceneValidityChecker>> validity(slots.size());
    auto install = [&](std::size_t c) {
        validity[c] = std::make_shared<SceneValidityChecker>(si, slots[c].scene, cfg.planar);
        si->setStateValidityChecker(validity[c]);
        if (slots[c].motion == MotionCheck::Continuous)
            si->setMotionValidator(std::make_shared<SceneMotionValidator>(si, validity[c]));
        else
            si->setMotionValidator(std::make_shared<ompl::base::DiscreteMotionValidator>(si));
    };
    ompl::tools::Benchmark benchmark(*planning.setup, cfg.name);
    std::map<const ompl::base::Planner *, std::size_t> slotOf;
    std::string labels;
    for (std::size_t c = 0; c < slots.size(); ++c)
    {
        install(c);
        labels += (c ? "," : "") + slots[c].label;
        std::vector<ompl::base::PlannerPtr> planners;
        for (const PlannerRequest &request : requests)
            planners.push_back(plannerForScene(request, si));
        requireDistinctPlannerNames(planners, cl, cfg);
        for (const ompl::base::PlannerPtr &planner : planners)
        {
            planner->setName(planner->getName() + "[" + slots[c].label + "]");
            slotOf[planner.get()] = c;
            benchmark.addPlanner(planner);
        }
    }
    benchmark.addExperimentParameter("configurations", "VARCHAR(512)", labels);
    benchmark.addExperimentParameter("baseline", "VARCHAR(64)", "none");
    benchmark.addExperimentParameter("robots", "INTEGER", std::to_string(cfg.robotCount()));
    benchmark.addExperimentParameter("shard_index", "INTEGER", std::to_string(run.shardIndex));
    benchmark.addExperimentParameter("shard_count", "INTEGER", std::to_string(run.shardCount));
    benchmark.addExperimentParameter("total_runs", "INTEGER", std::to_string(run.totalRuns));
    if (run.seeded)
    {
        benchmark.addExperimentParameter("base_seed", "INTEGER", std::to_string(run.baseSeed));
        benchmark.addExperimentParameter("shard_seed", "INTEGER", std::to_string(run.seed));
    }
    const std::size_t totalThisShard = std::size_t(run.shardRuns) * slotOf.size();
    std::size_t done = 0;
    std::map<const ompl::base::Planner *, unsigned> runsSoFar;
    // A run that overruns its limit by far ends the benchmark, with nothing written (planner_watchdog.h).
    PlannerWatchdog watchdog(kBadInput);
    benchmark.setPreRunEvent([&](const ompl::base::PlannerPtr &planner) {
        install(slotOf.at(planner.get()));
        watchdog.arm(planner->getName(), run.timeLimit, PlannerWatchdog::benchmarkGraceSeconds(run.timeLimit));
    });
    benchmark.setPostRunEvent([&](const ompl::base::PlannerPtr &planner, ompl::tools::Benchmark::RunProperties &props) {
        watchdog.disarm();
        const std::size_t c = slotOf.at(planner.get());
        const unsigned local = runsSoFar[planner.get()]++;
        props["collision checks INTEGER"] = std::to_string(validity[c]->checkCount());
        props["collision checking time REAL"] = std::to_string(validity[c]->checkSeconds());
        props["checker VARCHAR(32)"] = slots[c].checker;
        props["configuration VARCHAR(64)"] = slots[c].label;
        props["run index INTEGER"] = std::to_string(run.shardIndex + std::size_t(local) * run.shardCount);
        ++done;
        std::cerr << "\r[" << done << "/" << totalThisShard << "] " << planner->getName() << " run " << local + 1 << "/"
                  << run.shardRuns << "   " << std::flush;
    });
    ompl::tools::Benchmark::Request request(run.timeLimit, run.memoryLimit, run.shardRuns, 0.05, false, false, true);
    benchmark.benchmark(request);
    watchdog.disarm();  // OMPL skips the post-run event of a run whose results it could not store
    std::cerr << '\n';
    AtomicFile log(run.out);
    if (!benchmark.saveResultsToStream(log.stream()))
        throw InputError(run.out, 0, "cannot write the benchmark log");
    log.commit();
    std::cout << "benchmark log written to: " << run.out << " (" << slotOf.size() << " planner/configuration pairs, "
              << run.shardRuns << " runs each, " << cfg.robotCount() << " robots; configurations: " << labels << ")\n";
    return kSuccess;
}
}  // namespace

void declareBench(CommandLine &cl)
{
    cl.positionals("PROBLEM.cfg", "the problem (OMPL.app's .cfg format); its [benchmark] section gives the defaults")
        .option("planner", "NAME[,NAME...]",
                "the planners (default: the .cfg's, else rrtconnect, or kpiece for a kinodynamic problem)")
        .option("runs", "N", "runs per planner and configuration, at most 4294967295 (default: the .cfg's run_count)")
        .option("time", "SECONDS", "time limit per run, at most 1e9 (default: the .cfg's time_limit)")
        .option("memory", "MB", "memory limit per run (default: the .cfg's mem_limit)")
        .option("shard", "I/N", "do only the runs whose index is I modulo N (0 <= I < N <= 4294967295)")
        .option("out", "FILE.log", "the benchmark log (default NAME.log, or NAME.shardI.log)")
        .option("motion", "continuous|discrete[,...]",
                "how the --checker checkers check motions; both gives both (default continuous)")
        .option("baseline", "omplapp|none",
                "also run OMPL.app's set-up, fcl+discrete(0.01): FCL and OMPL's DiscreteMotionValidator "
                "(default omplapp)")
        .option("neighbors", "poses|ompl",
                "nearest neighbours of rrtconnect, rrt, prm and prmstar in hybridcd's configurations (default poses); "
                "OMPL.app's set-up always plans with ompl's default")
        .option("goal-threshold", "D",
                "kinodynamic problems: distance to the goal state that counts (default 1, OMPL.app's)")
        .option("seed", "N",
                "seed OMPL's random numbers (1 to 4294967295); shards derive theirs from it (default 1 with --shard)");
    addCheckerOptions(cl, true);
    cl.footer(R"(
Every --checker runs with every --motion, and OMPL.app's set-up is added as the baseline. Each
configuration is named in the log after its checker and motion check, e.g.
RRTConnect[obb+continuous], RRTConnect[obb+discrete(0.01)], RRTConnect[fcl+discrete(0.01)]
(OMPL.app: FCL, OMPL's DiscreteMotionValidator at resolution 0.01).
Writes an OMPL benchmark log, readable by ompl_benchmark_statistics.
A kinodynamic problem (control = ...) runs OMPL's control planners (kpiece by default, rrt, sst, est,
pdst) on OMPL.app's vehicle: continuous certifies whole trajectories, discrete(0.2s) checks the
states at the 0.2 s propagation steps only, as OMPL.app does; its baseline is fcl+discrete(0.2s).
Examples:
  hybridcd bench problems/window_3d.cfg --runs 20 --time 10
  hybridcd bench problems/window_3d.cfg --checker obb,hybrid --motion continuous,discrete --runs 20
  hybridcd bench problems/window_3d.cfg --runs 100 --shard 0/4 --seed 7 --out window.shard0.log
  hybridcd bench problems/corridor_kcar.cfg --planner kpiece,rrt --runs 10 --time 20
A scene problem (robot.K, obstacle.K) plans all its robots at once; it has no OMPL.app baseline, so
compare checkers and motion checks with --checker and --motion continuous,discrete.
Shard I of N (N > 1) seeds OMPL with SplitMix64(SEED * 2^32 + I) folded into 1..2^32-1, printed
and written in the log; bench/merge_shards.py merges the shards' logs into one experiment.
)");
}

int runBench(const CommandLine &cl, const CheckerCatalogue &checkers)
{
    if (cl.text("planner", "") == "help")  // as solve lists them
    {
        for (const std::string &n : plannerNames())
            std::cout << n << '\n';
        return kSuccess;
    }
    const auto [shardIndex, shardCount] = parseShard(cl.text("shard", "0/1"));
    // Shards are seeded from one base seed, so that a sharded benchmark is repeatable and no two
    // shards draw the same samples.
    const bool seeded = cl.has("seed") || shardCount > 1;
    const std::uint_fast32_t baseSeed = cl.has("seed") ? seedOf(cl) : 1;
    const std::uint_fast32_t seed = shardSeed(baseSeed, shardIndex, shardCount);
    if (seeded)
        ompl::RNG::setSeed(seed);
    const LoadedProblem problem = loadProblemFor(cl);
    const ProblemConfig &cfg = problem.config;
    // A kinodynamic problem (control = ...) is benchmarked with OMPL's control planners.
    const bool kinodynamic = !cfg.control.empty();
    std::vector<CheckerSlot> slots = configurationsOf(cl, checkers, kinodynamic, cfg.isScene());
    if (!kinodynamic && cl.has("goal-threshold"))
        throw UsageError("--goal-threshold is for kinodynamic problems (a .cfg with control = ...)");
    ControlSettings controlSettings;
    controlSettings.goalThreshold = cl.positiveNumber("goal-threshold", controlSettings.goalThreshold);

    // OMPL counts runs in unsigned.
    const long long totalRuns =
        cl.positiveInteger("runs", cfg.benchmark.runCount, std::numeric_limits<unsigned>::max());
    // Shard I of N does the runs whose index is I modulo N, so shards never overlap and together
    // make exactly the whole benchmark.
    const unsigned shardRuns = unsigned((totalRuns - shardIndex + shardCount - 1) / shardCount);
    const double timeLimit = cl.timeLimit("time", cfg.benchmark.timeLimit);
    const NeighborSearch neighbors = neighborSearchOf(cl);
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
        requests.push_back({kinodynamic ? "kpiece" : "rrtconnect", "", {}});

    if (cfg.isScene())
        return benchScene(cl, problem, slots, requests,
                          SceneBenchRun{timeLimit, memoryLimit, shardRuns, shardIndex, shardCount, totalRuns, seeded,
                                        baseSeed, seed, out});
    for (CheckerSlot &slot : slots)
        slot.instance = checkers.make(slot.checker, problem.scene, slot.options);

    // One SimpleSetup for every configuration; `install` points it at a configuration's checker and
    // motion check, `plannerOf` makes a planner on it.
    std::optional<PlanningProblem> geometric;
    std::optional<ControlProblem> control;
    std::unique_ptr<ompl::tools::Benchmark> benchmarkPtr;
    std::function<std::shared_ptr<StateValidityChecker>(const CheckerSlot &)> install;
    std::function<ompl::base::PlannerPtr(const PlannerRequest &, const CheckerSlot &)> plannerOf;
    if (kinodynamic)
    {
        controlSettings.motion = slots.front().motion;
        control = makeControlProblem(problem, slots.front().instance, controlSettings);
        install = [&](const CheckerSlot &slot) {
            return installControlChecker(*control, problem, slot.instance, slot.motion);
        };
        plannerOf = [&](const PlannerRequest &request, const CheckerSlot &) {
            return makeControlPlanner(request, control->setup->getSpaceInformation());
        };
        benchmarkPtr = std::make_unique<ompl::tools::Benchmark>(*control->setup, cfg.name);
    }
    else
    {
        geometric = makePlanningProblem(problem, slots.front().instance, slots.front().motion);
        geometric->setup->getSpaceInformation()->setStateValidityCheckingResolution(kResolution);
        install = [&](const CheckerSlot &slot) {
            return installChecker(*geometric, problem, slot.instance, slot.motion);
        };
        plannerOf = [&](const PlannerRequest &request, const CheckerSlot &slot) {
            return makePlanner(request, geometric->setup->getSpaceInformation(),
                               slot.omplAppSetup ? NeighborSearch::OmplDefault : neighbors);
        };
        benchmarkPtr = std::make_unique<ompl::tools::Benchmark>(*geometric->setup, cfg.name);
    }
    // Every configuration must see a free start and goal: FCL calls a robot inside a closed
    // obstacle free, the solid checkers do not.
    for (CheckerSlot &slot : slots)
    {
        slot.validity = install(slot);
        if (kinodynamic)
            requireCollisionFreeStartAndGoal(problem, control->poseSpace, *control->poseValidity);
        else
            requireCollisionFreeStartAndGoal(problem, *geometric);
    }

    ompl::tools::Benchmark &benchmark = *benchmarkPtr;
    std::map<const ompl::base::Planner *, std::size_t> slotOf;
    std::string labels;
    for (std::size_t c = 0; c < slots.size(); ++c)
    {
        labels += (c ? "," : "") + slots[c].label;
        std::vector<ompl::base::PlannerPtr> planners;
        for (const PlannerRequest &request : requests)
            planners.push_back(plannerOf(request, slots[c]));
        requireDistinctPlannerNames(planners, cl, cfg);
        for (const ompl::base::PlannerPtr &planner : planners)
        {
            // The configuration in the name keeps set-ups apart when logs are merged into one database.
            planner->setName(planner->getName() + "[" + slots[c].label + "]");
            slotOf[planner.get()] = c;
            benchmark.addPlanner(planner);
        }
    }
    benchmark.addExperimentParameter("configurations", "VARCHAR(512)", labels);
    benchmark.addExperimentParameter("baseline", "VARCHAR(64)",
                                     cl.text("baseline", "omplapp") == "omplapp" ? "fcl+" + discreteLabel(kinodynamic)
                                                                                 : "none");
    if (kinodynamic)
    {
        benchmark.addExperimentParameter("control", "VARCHAR(32)", cfg.control);
        benchmark.addExperimentParameter("goal_threshold", "REAL", shortNumber(controlSettings.goalThreshold));
    }
    benchmark.addExperimentParameter("shard_index", "INTEGER", std::to_string(shardIndex));
    benchmark.addExperimentParameter("neighbors", "VARCHAR(16)", cl.text("neighbors", "poses"));
    benchmark.addExperimentParameter("shard_count", "INTEGER", std::to_string(shardCount));
    benchmark.addExperimentParameter("total_runs", "INTEGER", std::to_string(totalRuns));
    if (seeded)
    {
        benchmark.addExperimentParameter("base_seed", "INTEGER", std::to_string(baseSeed));
        benchmark.addExperimentParameter("shard_seed", "INTEGER", std::to_string(seed));
    }
    if (shardCount > 1)
        std::cout << "shard " << shardIndex << "/" << shardCount << ": seed " << seed << " (derived from base seed "
                  << baseSeed << ")" << std::endl;

    const std::size_t totalThisShard = std::size_t(shardRuns) * slotOf.size();
    std::size_t done = 0;
    std::map<const ompl::base::Planner *, unsigned> runsSoFar;
    // A run that overruns its limit by far ends the benchmark, with nothing written (planner_watchdog.h).
    PlannerWatchdog watchdog(kBadInput);
    benchmark.setPreRunEvent([&](const ompl::base::PlannerPtr &planner) {
        // Point the space at this configuration's checker and motion validator, and zero its counters.
        CheckerSlot &slot = slots[slotOf.at(planner.get())];
        slot.validity = install(slot);
        slot.validity->resetCounters();
        watchdog.arm(planner->getName(), timeLimit, PlannerWatchdog::benchmarkGraceSeconds(timeLimit));
    });
    benchmark.setPostRunEvent([&](const ompl::base::PlannerPtr &planner, ompl::tools::Benchmark::RunProperties &run) {
        watchdog.disarm();
        const CheckerSlot &slot = slots[slotOf.at(planner.get())];
        const unsigned local = runsSoFar[planner.get()]++;
        run["collision checks INTEGER"] = std::to_string(slot.validity->checkCount());
        run["collision checking time REAL"] = std::to_string(slot.validity->checkSeconds());
        run["checker VARCHAR(32)"] = slot.checker;
        run["configuration VARCHAR(64)"] = slot.label;
        run["run index INTEGER"] = std::to_string(shardIndex + std::size_t(local) * shardCount);
        ++done;
        std::cerr << "\r[" << done << "/" << totalThisShard << "] " << planner->getName() << " run " << local + 1 << "/"
                  << shardRuns << "   " << std::flush;
    });

    ompl::tools::Benchmark::Request request(timeLimit, memoryLimit, shardRuns, 0.05, false, false, true);
    benchmark.benchmark(request);
    watchdog.disarm();  // OMPL skips the post-run event of a run whose results it could not store
    std::cerr << '\n';

    AtomicFile log(out);
    if (!benchmark.saveResultsToStream(log.stream()))
        throw InputError(out, 0, "cannot write the benchmark log");
    log.commit();
    std::cout << "benchmark log written to: " << out << " (" << slotOf.size() << " planner/configuration pairs, "
              << shardRuns << " runs each; configurations: " << labels << ")\n";
    return kSuccess;
}
}  // namespace hcd::cli
