// SPDX-License-Identifier: BSD-3-Clause
// check, check-motion, clearance and solve on scene problems (several robots, obstacles of their
// own): every robot's pose on each line, robot 1 first (README, "Scenes of many bodies").
#include "command_scene.h"
#include "commands.h"
#include "motion_verdicts.h"
#include "planner_watchdog.h"
#include "problem_checks.h"

#include "hybridcd/io/atomic_file.h"
#include "hybridcd/io/input_error.h"
#include "hybridcd/io/path_file.h"
#include "hybridcd/io/pose_codec.h"
#include "hybridcd/ompl/scene_planning.h"
#include "hybridcd/planners/planner_catalogue.h"
#include "hybridcd/scene/problem_bodies.h"

#include <ompl/geometric/PathGeometric.h>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace hcd::cli
{
namespace
{
using Clock = std::chrono::steady_clock;

// The robots' transforms of one line (robot 1 first).
std::vector<RigidTransform> posesOfLine(const std::vector<double> &values, const ProblemConfig &config)
{
    const std::size_t columns = poseColumns(config.planar);
    std::vector<RigidTransform> poses;
    for (std::size_t r = 0; r < config.robotCount(); ++r)
        poses.push_back(transformOfRow(values.data() + r * columns, config.planar));
    return poses;
}

void describe(const LoadedProblem &problem, const Scene &scene, std::ostream &out)
{
    out << "scene: " << problem.config.robotCount() << " robot" << (problem.config.robotCount() == 1 ? "" : "s") << ", "
        << scene.bodies().size() << " bodies, " << scene.pairs().size() << " checked pairs\n";
}

}  // namespace

SceneOptions sceneOptionsOf(const std::string &checkerName, const CheckerOptions &options)
{
    SceneOptions scene;
    scene.bruteForce = checkerName == "bruteforce";
    scene.meshChecker = checkerName;
    scene.meshCheckerOptions = options;
    return scene;
}

void requireFreeEnds(const LoadedProblem &problem, const Scene &scene)
{
    QueryContext context;
    for (const bool isStart : {true, false})
    {
        const std::vector<RigidTransform> poses = isStart ? problemStart(problem.config) : problemGoal(problem.config);
        if (const auto contact = scene.firstContact(poses.data(), context))
        {
            std::size_t pair = 0;
            while (scene.pairs()[pair].first != contact->pair.first ||
                   scene.pairs()[pair].second != contact->pair.second)
                ++pair;
            throw InputError(problem.config.path, isStart ? problem.config.startLine : problem.config.goalLine,
                             std::string("the ") + (isStart ? "start" : "goal") +
                                 " state collides: " + scene.pairLabel(pair));
        }
    }
}

int runSceneCheck(const LoadedProblem &problem, const std::string &statesPath, const std::string &checkerName,
                  const CheckerOptions &options)
{
    const ProblemConfig &config = problem.config;
    const auto records = readPoses(statesPath, config.planar, config.robotCount());
    const auto scene = makeProblemScene(problem, sceneOptionsOf(checkerName, options));
    std::string out;
    std::size_t free = 0;
    QueryContext context;
    const auto start = Clock::now();
    for (const PoseRecord &record : records)
    {
        const bool collides = scene->collides(posesOfLine(record.values, config), context);
        free += collides ? 0 : 1;
        out += collides ? "0\n" : "1\n";
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::cout << out << std::flush;
    describe(problem, *scene, std::cerr);
    std::cerr << "checked " << records.size() << " states with '" << checkerName << "': " << free << " free, "
              << records.size() - free << " colliding; mean "
              << (records.empty() ? 0.0 : 1e9 * seconds / double(records.size())) << " ns per check\n";
    return 0;
}

int runSceneClearance(const LoadedProblem &problem, const std::string &statesPath, const std::string &checkerName,
                      const CheckerOptions &options)
{
    const ProblemConfig &config = problem.config;
    const auto records = readPoses(statesPath, config.planar, config.robotCount());
    const auto scene = makeProblemScene(problem, sceneOptionsOf(checkerName, options));
    std::ostringstream out;
    out << std::setprecision(std::numeric_limits<double>::max_digits10);
    QueryContext context;
    std::size_t free = 0;
    const auto start = Clock::now();
    for (const PoseRecord &record : records)
    {
        const std::vector<RigidTransform> poses = posesOfLine(record.values, config);
        const double d = scene->distance(poses.data(), context);
        free += d > 0.0 ? 1 : 0;
        out << d << '\n';
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::cout << out.str();
    std::cerr << "computed the clearance of " << records.size() << " states with '" << checkerName << "': " << free
              << " free, " << records.size() - free << " touching; mean "
              << (records.empty() ? 0.0 : 1e9 * seconds / double(records.size())) << " ns per clearance\n";
    return 0;
}

std::optional<std::size_t> runSceneCheckMotion(const LoadedProblem &problem,
                                               const std::vector<std::pair<PoseRecord, PoseRecord>> &motions,
                                               const std::string &checkerName, const CheckerOptions &options,
                                               bool verdictOnly)
{
    const ProblemConfig &config = problem.config;
    const auto scene = makeProblemScene(problem, sceneOptionsOf(checkerName, options));
    MotionVerdicts verdicts(verdictOnly);
    QueryContext context;
    std::size_t lpPairs = 0, distances = 0;
    const auto start = Clock::now();
    for (const auto &[from, to] : motions)
    {
        SceneMotionOptions motionOptions;
        motionOptions.verdictOnly = verdictOnly;
        motionOptions.planar = config.planar;
        const SceneMotionResult result = checkSceneMotion(*scene, posesOfLine(from.values, config),
                                                          posesOfLine(to.values, config), context, motionOptions);
        lpPairs += result.lpPairs;
        distances += result.distanceQueries;
        verdicts.add(result.valid, result.lastValidTime);
    }
    verdicts.print(checkerName, std::chrono::duration<double>(Clock::now() - start).count(),
                   " (" + std::to_string(distances) + " distance queries, " + std::to_string(lpPairs) +
                       " pairs by the time-augmented LP)");
    return verdicts.firstBlocked();
}

ompl::base::PlannerPtr plannerForScene(const PlannerRequest &request, const ompl::base::SpaceInformationPtr &si)
{
    try
    {
        return makePlanner(request, si);
    }
    catch (const std::invalid_argument &e)
    {
        throw std::invalid_argument("--planner " + request.type + ": " + e.what());
    }
}

int runSceneSolve(const LoadedProblem &problem, const SceneSolveRun &run)
{
    const auto buildStart = Clock::now();
    const auto scene = makeProblemScene(problem, sceneOptionsOf(run.checkerName, run.checkerOptions));
    const double buildSeconds = std::chrono::duration<double>(Clock::now() - buildStart).count();
    requireFreeEnds(problem, *scene);
    ScenePlanningProblem planning = makeScenePlanningProblem(problem, scene, run.continuous);
    PlannerRequest request{run.plannerName, "", run.params};
    planning.setup->setPlanner(plannerForScene(request, planning.setup->getSpaceInformation()));
    planning.setup->setup();
    const ompl::base::PlannerStatus status = solveWatched(*planning.setup, run.timeLimit, run.timeLimit, kNotSolved);
    const bool solved = status == ompl::base::PlannerStatus::EXACT_SOLUTION;
    const bool approximate =
        status == ompl::base::PlannerStatus::APPROXIMATE_SOLUTION && planning.setup->haveSolutionPath();
    const std::size_t robots = problem.config.robotCount();
    std::cout << "problem: " << problem.config.name << " (" << robots << " robots, "
              << (problem.config.planar ? "SE2" : "SE3") << " each)\n";
    describe(problem, *scene, std::cout);
    std::cout << "checker: " << run.checkerName << " for mesh pairs (built in " << buildSeconds * 1e3 << " ms)\n"
              << "planner: " << planning.setup->getPlanner()->getName() << '\n'
              << "motion check: " << (run.continuous ? "continuous" : "discrete") << '\n'
              << "solved: "
              << (solved        ? "yes"
                  : approximate ? "no, approximate path only"
                                : "no")
              << " (" << status.asString() << ")\n"
              << "solve time: " << planning.setup->getLastPlanComputationTime() << " s\n"
              << "collision checks: " << planning.validity->checkCount() << '\n';
    if (!solved && !approximate)
        return 2;
    planning.setup->simplifySolution();
    ompl::geometric::PathGeometric &path = planning.setup->getSolutionPath();
    std::cout << "simplified path length: " << path.length() << '\n' << "path states: " << path.getStateCount() << '\n';
    path.interpolate();
    std::vector<std::vector<double>> rows;
    for (std::size_t i = 0; i < path.getStateCount(); ++i)
        rows.push_back(sceneRowsOfState(path.getState(i), problem.config.planar, robots));
    AtomicFile out(run.outPath);
    writePoses(out.stream(), rows);
    out.commit();
    std::cout << "states written (interpolated at OMPL's resolution; " << robots << " poses per line): " << rows.size()
              << '\n'
              << (approximate ? "APPROXIMATE path written to: " : "path written to: ") << run.outPath << '\n';
    if (approximate)
    {
        std::cerr << "hybridcd: warning: no exact solution in " << run.timeLimit << " s; " << run.outPath
                  << " holds an APPROXIMATE path (exit status 2)\n";
        return 2;
    }
    return 0;
}
}  // namespace hcd::cli
