// SPDX-License-Identifier: BSD-3-Clause
// `hybridcd solve`: plan, simplify, report, write the path in OMPL.app's .path format.
#include "command_line.h"
#include "command_scene.h"
#include "commands.h"
#include "planner_watchdog.h"
#include "problem_checks.h"
#include "solve_progress.h"

#include "hybridcd/io/atomic_file.h"
#include "hybridcd/io/input_error.h"
#include "hybridcd/io/path_file.h"
#include "hybridcd/ompl/control_problem.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/ompl/retraction_sampler.h"
#include "hybridcd/planners/planner_catalogue.h"
#include "hybridcd/query/checker_catalogue.h"

#include <ompl/control/PathControl.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <tuple>
#include <unistd.h>

namespace hcd::cli
{
namespace
{
// "k=v,k2=v2" into ordered pairs.
std::vector<std::pair<std::string, std::string>> parseParams(const std::string &text)
{
    std::vector<std::pair<std::string, std::string>> out;
    std::stringstream items(text);
    std::string item;
    while (std::getline(items, item, ','))
    {
        if (item.empty())
            continue;
        const auto eq = item.find('=');
        if (eq == std::string::npos || eq == 0)
            throw UsageError("--param expects KEY=VALUE[,KEY=VALUE...], got '" + item + "'");
        out.emplace_back(item.substr(0, eq), item.substr(eq + 1));
    }
    return out;
}
// "MIN,MAX" propagation steps per control.
std::pair<unsigned, unsigned> parseControlSteps(const std::string &text)
{
    const auto comma = text.find(',');
    auto whole = [&](const std::string &item) -> unsigned {
        char *end = nullptr;
        const unsigned long v = std::strtoul(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || item[0] == '-' || v < 1 || v > 100000)
            throw UsageError("--control-steps expects MIN,MAX whole numbers from 1 to 100000, got '" + text + "'");
        return unsigned(v);
    };
    if (comma == std::string::npos)
        throw UsageError("--control-steps expects MIN,MAX, got '" + text + "'");
    const unsigned lo = whole(text.substr(0, comma)), hi = whole(text.substr(comma + 1));
    if (lo > hi)
        throw UsageError("--control-steps: MIN exceeds MAX in '" + text + "'");
    return {lo, hi};
}

// The longest propagation step taken (seconds; the message below names it).
constexpr double kMaxPropagationStep = 10.0;

struct ControlRun
{
    double timeLimit;
    std::string outPath;
    std::string plannerName;
    std::vector<std::pair<std::string, std::string>> params;
    ControlSettings settings;
};

// A kinodynamic problem: OMPL's control planners on OMPL.app's vehicle model.
int solveControl(const LoadedProblem &problem, std::shared_ptr<const CollisionChecker> checker, double buildSeconds,
                 const ControlRun &run)
{
    const std::string checkerName = checker->name();
    ControlProblem planning = makeControlProblem(problem, std::move(checker), run.settings);
    requireCollisionFreeStartAndGoal(problem, planning.poseSpace, *planning.poseValidity);
    PlannerRequest request{run.plannerName, "", run.params};
    planning.setup->setPlanner(makeControlPlanner(request, planning.setup->getSpaceInformation()));
    planning.setup->setup();

    const ompl::base::PlannerStatus status = solveWatched(*planning.setup, run.timeLimit, run.timeLimit, kNotSolved);
    const bool solved = status == ompl::base::PlannerStatus::EXACT_SOLUTION;
    // As for geometric planners: the path OMPL keeps nearest the goal is written, labelled.
    const bool approximate =
        status == ompl::base::PlannerStatus::APPROXIMATE_SOLUTION && planning.setup->haveSolutionPath();
    const double solveSeconds = planning.setup->getLastPlanComputationTime();
    const std::uint64_t checks = planning.poseValidity->checkCount();
    const double checkSeconds = planning.poseValidity->checkSeconds();
    std::cout << "problem: " << problem.config.name << " (" << vehicleModelName(planning.model) << ", "
              << (problem.config.planar ? "SE2" : "SE3") << " pose)\n"
              << "checker: " << checkerName << " (built in " << buildSeconds * 1e3 << " ms)\n"
              << "planner: " << planning.setup->getPlanner()->getName() << " (control)\n"
              << "motion check: "
              << (run.settings.motion == MotionCheck::Continuous ? "continuous (every integration step)"
                                                                 : "discrete (propagation steps)")
              << '\n'
              << "propagation step: " << run.settings.propagationStep << " s, controls of "
              << run.settings.minControlSteps << " to " << run.settings.maxControlSteps << " steps\n"
              << "goal threshold: " << run.settings.goalThreshold << '\n'
              << "solved: "
              << (solved        ? "yes"
                  : approximate ? "no, approximate path only"
                                : "no")
              << " (" << status.asString() << ")\n"
              << "solve time: " << solveSeconds << " s\n"
              << "collision checks: " << checks << '\n'
              << "collision checking time: " << checkSeconds << " s\n";
    if (!solved && !approximate)
        return kNotSolved;

    ompl::control::PathControl &path = planning.setup->getSolutionPath();
    std::cout << "controls: " << path.getControlCount() << '\n' << "duration: " << path.length() << " s\n";
    // One row per propagation step, as OMPL.app writes control paths (PathControl::printAsMatrix):
    // the state, then the control applied from it and for how long; the last row has zero controls.
    path.interpolate();
    const auto space = planning.setup->getStateSpace();
    const unsigned controlDims = planning.setup->getControlSpace()->getDimension();
    std::vector<std::vector<double>> rows;
    for (std::size_t i = 0; i < path.getStateCount(); ++i)
    {
        std::vector<double> row;
        space->copyToReals(row, path.getState(i));
        for (unsigned k = 0; k < controlDims; ++k)
            row.push_back(i < path.getControlCount()
                              ? path.getControl(i)->as<ompl::control::RealVectorControlSpace::ControlType>()->values[k]
                              : 0.0);
        row.push_back(i < path.getControlCount() ? path.getControlDuration(i) : 0.0);
        rows.push_back(std::move(row));
    }
    // The state's values as written (copyToReals): a quaternion counts four, where the space's
    // dimension counts three.
    std::vector<double> stateValues;
    space->copyToReals(stateValues, path.getState(0));
    AtomicFile out(run.outPath);
    out.stream() << "# " << vehicleModelName(planning.model) << " path: " << stateValues.size()
                 << " state values (the pose first, as in OMPL.app's .path), " << controlDims
                 << " control values, duration in s\n";
    writePoses(out.stream(), rows);
    out.commit();
    std::cout << "states written (one per propagation step): " << rows.size() << '\n';
    if (!approximate)
    {
        std::cout << "path written to: " << run.outPath << '\n';
        return kSuccess;
    }
    const double goalDistance = planning.setup->getProblemDefinition()->getSolutionDifference();
    std::cout << "approximate path: ends " << goalDistance << " from the goal (OMPL's goal distance)\n"
              << "APPROXIMATE path written to: " << run.outPath << '\n';
    std::cerr << "hybridcd: warning: no exact solution in " << run.timeLimit << " s; " << run.outPath
              << " holds an APPROXIMATE path, which ends " << goalDistance << " from the goal (exit status 2)\n";
    return kNotSolved;
}
}  // namespace

void declareSolve(CommandLine &cl)
{
    cl.positionals("PROBLEM.cfg", "the problem (OMPL.app's .cfg format)")
        .option("planner", "NAME", "the OMPL planner (default rrtconnect); 'help' lists them")
        .option("time", "SECONDS", "the planning time limit, at most 1e9 (default 10)")
        .option("seed", "N", "seed OMPL's random numbers (1 to 4294967295) for a repeatable run")
        .option("out", "PATH_FILE", "where to write the path (default NAME.solution.path here)")
        .option("param", "KEY=VALUE[,...]", "planner parameters, e.g. range=5,intermediate_states=1")
        .option("motion", "continuous|discrete", "how motions are checked (default continuous)")
        .option("sampler", "uniform|retraction",
                "state sampling (default uniform); retraction pushes colliding samples out onto the "
                "obstacles' surfaces")
        .option("neighbors", "poses|ompl",
                "nearest neighbours of rrtconnect, rrt, prm, prmstar (default poses: a k-d tree over the poses, the "
                "same neighbours as ompl's default GNAT, found with fewer distances)")
        .option("goal-threshold", "D", "kinodynamic problems: distance to the goal state that counts (default 1)")
        .option("propagation-step", "SECONDS", "kinodynamic problems: the propagation step, at most 10 (default 0.2)")
        .option("control-steps", "MIN,MAX", "kinodynamic problems: steps each control lasts (default 1,20)")
        .flag("verbose", "OMPL's progress messages")
        .flag("quiet", "no progress on stderr (default: a line a second, or a bar on a terminal)");
    addCheckerOptions(cl, false);
    cl.footer(R"(
Examples:
  hybridcd solve problems/window_3d.cfg --seed 1 --time 30
  hybridcd solve problems/corridor_2d.cfg --planner kpiece --param range=5 --out corridor.path

A scene problem (robot.K, obstacle.K) is planned for all its robots at once on the compound space;
each line of the path holds every robot's pose, robot 1 first.
A problem with `control = kinematic_car|dynamic_car|blimp|quadrotor` is planned with OMPL's control
planners (kpiece (default), rrt, sst, est, pdst) on OMPL.app's vehicle model.
)");
}

int runSolve(const CommandLine &cl, const CheckerCatalogue &checkers)
{
    if (cl.text("planner", "") == "help")
    {
        for (const std::string &n : plannerNames())
            std::cout << n << '\n';
        return kSuccess;
    }
    // Every option is checked before anything is loaded or planned.
    // The seed must be set before OMPL creates its first random number generator.
    if (cl.has("seed"))
        ompl::RNG::setSeed(seedOf(cl));
    if (cl.has("verbose"))
        ompl::msg::setLogLevel(ompl::msg::LOG_INFO);
    const double timeLimit = cl.timeLimit("time", 10.0);
    const CheckerOptions checkerOptions = checkerOptionsOf(cl);
    const std::string checkerName = checkerNamesOf(cl, checkers, checkerOptions).front();
    const MotionCheck motion = parseMotionCheck(cl.text("motion", "continuous"));
    const auto params = parseParams(cl.text("param", ""));
    const std::string sampling = cl.text("sampler", "uniform");
    if (sampling != "uniform" && sampling != "retraction")
        throw UsageError("option --sampler needs uniform or retraction, got '" + sampling + "'");
    const NeighborSearch neighbors = neighborSearchOf(cl);

    ControlSettings controlSettings;
    controlSettings.motion = motion;
    controlSettings.goalThreshold = cl.positiveNumber("goal-threshold", controlSettings.goalThreshold);
    controlSettings.propagationStep = cl.positiveNumber("propagation-step", controlSettings.propagationStep);
    // Each step is integrated finely and a control lasts up to --control-steps of them: a step of
    // hours would keep one propagation running past any time limit. OMPL.app's vehicles use 0.1-0.2 s.
    if (controlSettings.propagationStep > kMaxPropagationStep)
        throw UsageError("option --propagation-step needs at most 10 seconds, got '" + cl.text("propagation-step", "") +
                         "'");
    if (cl.has("control-steps"))
        std::tie(controlSettings.minControlSteps, controlSettings.maxControlSteps) =
            parseControlSteps(cl.text("control-steps", ""));

    const LoadedProblem problem = loadProblemFor(cl);
    // The default name cannot be OMPL.app's NAME.path, which its problem folders ship as samples.
    const std::string outPath = cl.text("out", problem.config.name + ".solution.path");
    checkOutputPath(outPath, cl.has("out") ? "--out" : "the default output", inputFilesOf(problem));
    requireStartAndGoalInVolume(problem.config);
    if (problem.config.isScene())
    {
        if (cl.has("sampler") && sampling != "uniform")
            throw UsageError("option --sampler retraction is for problems of one robot; " + problem.config.name +
                             " is a scene of " + std::to_string(problem.config.robotCount()) + " robots");
        for (const char *option : {"goal-threshold", "propagation-step", "control-steps"})
            if (cl.has(option))
                throw UsageError(std::string("--") + option +
                                 " is for kinodynamic problems (a .cfg with control = ...)");
        SceneSolveRun run;
        run.timeLimit = timeLimit;
        run.outPath = outPath;
        run.plannerName = cl.text("planner", "rrtconnect");
        run.params = params;
        run.checkerName = checkerName;
        run.checkerOptions = checkerOptions;
        run.continuous = motion == MotionCheck::Continuous;
        return runSceneSolve(problem, run);
    }

    const auto buildStart = std::chrono::steady_clock::now();
    std::shared_ptr<const CollisionChecker> checker = checkers.make(checkerName, problem.scene, checkerOptions);
    const double buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - buildStart).count();

    for (const char *option : {"sampler", "neighbors"})
        if (!problem.config.control.empty() && cl.has(option))
            throw UsageError(std::string("option --") + option + " is for geometric problems; " + problem.config.name +
                             " is kinodynamic (control = " + problem.config.control + ")");
    if (!problem.config.control.empty())
        return solveControl(problem, checker, buildSeconds,
                            ControlRun{timeLimit, outPath, cl.text("planner", "kpiece"), params, controlSettings});
    for (const char *option : {"goal-threshold", "propagation-step", "control-steps"})
        if (cl.has(option))
            throw UsageError(std::string("--") + option + " is for kinodynamic problems (a .cfg with control = ...)");
    PlanningProblem planning = makePlanningProblem(problem, checker, motion);
    requireCollisionFreeStartAndGoal(problem, planning);
    if (sampling == "retraction")
        useRetractionSampling(planning);
    PlannerRequest request{cl.text("planner", "rrtconnect"), "", params};
    planning.setup->setPlanner(makePlanner(request, planning.setup->getSpaceInformation(), neighbors));
    planning.setup->setup();

    SolveProgress::Options progressOptions;
    progressOptions.timeLimit = timeLimit;
    progressOptions.quiet = cl.has("quiet");
    progressOptions.terminal = ::isatty(STDERR_FILENO) == 1;
    SolveProgress progress(planning, std::cerr, progressOptions);
    const ompl::base::PlannerStatus status = solveWatched(*planning.setup, progress.start(), timeLimit, kNotSolved);
    const bool solved = status == ompl::base::PlannerStatus::EXACT_SOLUTION;
    // OMPL keeps the path that ends nearest the goal when it finds no exact one.
    const bool approximate =
        status == ompl::base::PlannerStatus::APPROXIMATE_SOLUTION && planning.setup->haveSolutionPath();
    progress.finish(solved ? "exact solution" : approximate ? "approximate solution only" : "no solution");
    const double solveSeconds = planning.setup->getLastPlanComputationTime();
    const std::uint64_t checks = planning.validity->checkCount();
    const double checkSeconds = planning.validity->checkSeconds();

    std::cout << "problem: " << problem.config.name << " (" << (problem.config.planar ? "SE2" : "SE3") << ")\n"
              << "checker: " << checker->name() << " (built in " << buildSeconds * 1e3 << " ms)\n"
              << "planner: " << planning.setup->getPlanner()->getName() << '\n'
              << "motion check: " << cl.text("motion", "continuous") << '\n'
              << "sampler: " << sampling << '\n'
              << "nearest neighbours: "
              << (searchesWithPoseNeighbors(*planning.setup->getPlanner()) ? "poses" : "ompl's default") << '\n'
              << "solved: "
              << (solved        ? "yes"
                  : approximate ? "no, approximate path only"
                                : "no")
              << " (" << status.asString() << ")\n"
              << "solve time: " << solveSeconds << " s\n"
              << "collision checks: " << checks << '\n'
              << "collision checking time: " << checkSeconds << " s"
              << (checks ? " (" + std::to_string(1e9 * checkSeconds / double(checks)) + " ns per check)" : "") << '\n';
    if (!solved && !approximate)
        return kNotSolved;

    planning.setup->simplifySolution();
    ompl::geometric::PathGeometric &path = planning.setup->getSolutionPath();
    const double goalDistance = planning.setup->getProblemDefinition()->getSolutionDifference();
    std::cout << "simplified path length: " << path.length() << '\n' << "path states: " << path.getStateCount() << '\n';
    if (approximate)
        std::cout << "approximate path: ends " << goalDistance << " from the goal (OMPL's goal distance)\n";
    // Written densely, as OMPL.app's sample paths are: states at OMPL's validity resolution, so a
    // reader that interpolates consecutive states another way stays close to the certified motion.
    path.interpolate();
    std::cout << "states written (interpolated at OMPL's resolution): " << path.getStateCount() << '\n';

    std::vector<std::vector<double>> rows;
    for (std::size_t i = 0; i < path.getStateCount(); ++i)
        rows.push_back(stateToPoseValues(path.getState(i), planning.planar));
    AtomicFile out(outPath);
    writePoses(out.stream(), rows);
    out.commit();
    if (!approximate)
    {
        std::cout << "path written to: " << outPath << '\n';
        return kSuccess;
    }
    // The .path file stays bare poses (OMPL.app reads it so); the label is in the output and the status.
    std::cout << "APPROXIMATE path written to: " << outPath << '\n';
    std::cerr << "hybridcd: warning: no exact solution in " << timeLimit << " s; " << outPath
              << " holds an APPROXIMATE path, which ends " << goalDistance << " from the goal (exit status 2)\n";
    return kNotSolved;
}
}  // namespace hcd::cli
