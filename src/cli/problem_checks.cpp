// SPDX-License-Identifier: BSD-3-Clause
#include "problem_checks.h"

#include "hybridcd/io/input_error.h"

#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace hcd::cli
{
namespace
{
std::string formatPose(const ConfigPose &p, bool planar)
{
    std::ostringstream s;
    s << "(" << p.x << ", " << p.y;
    if (!planar)
        s << ", " << p.z;
    s << ")";
    return s.str();
}
}  // namespace

NeighborSearch neighborSearchOf(const CommandLine &cl)
{
    const std::string name = cl.text("neighbors", "poses");
    try
    {
        return parseNeighborSearch(name);
    }
    catch (const std::invalid_argument &)
    {
        throw UsageError("option --neighbors needs poses or ompl, got '" + name + "'");
    }
}

LoadedProblem loadProblemFor(const CommandLine &cl)
{
    MeshLimits limits;
    // Bounded so that the file-size bound (128 bytes a triangle) and 32-bit vertex indices cannot overflow.
    limits.maxTriangles =
        std::size_t(cl.positiveInteger("max-triangles", (long long)(limits.maxTriangles), 1'000'000'000));
    LoadedProblem problem = loadProblem(cl.problem(), limits);
    for (const std::string &warning : problem.config.warnings)
        std::cerr << "hybridcd: warning: " << printable(warning, true) << '\n';
    return problem;
}

std::vector<std::string> inputFilesOf(const LoadedProblem &problem)
{
    return {problem.config.path, problem.config.robotMesh, problem.config.worldMesh};
}

void requireStartAndGoalInVolume(const ProblemConfig &config)
{
    const std::optional<std::pair<double, double>> volume[3] = {config.volumeX, config.volumeY, config.volumeZ};
    const char *axes[3] = {"x", "y", "z"};
    struct End
    {
        const ConfigPose *pose;
        int line;
        std::string name;
    };
    std::vector<End> ends = {{&config.start, config.startLine, "start"}, {&config.goal, config.goalLine, "goal"}};
    for (const RobotSpec &robot : config.extraRobots)
    {
        const std::string k = robot.label.substr(robot.label.find('.') + 1);
        ends.push_back({&robot.start, robot.startLine, "start." + k});
        ends.push_back({&robot.goal, robot.goalLine, "goal." + k});
    }
    for (const End &end : ends)
    {
        const ConfigPose &pose = *end.pose;
        const double position[3] = {pose.x, pose.y, pose.z};
        for (int i = 0; i < (config.planar ? 2 : 3); ++i)
            if (volume[i] && (position[i] < volume[i]->first || position[i] > volume[i]->second))
            {
                std::ostringstream message;
                message << "the " << end.name << " " << formatPose(pose, config.planar)
                        << " lies outside the problem's volume: " << end.name << "." << axes[i] << " = " << position[i]
                        << " is not in [volume.min." << axes[i] << ", volume.max." << axes[i] << "] = ["
                        << volume[i]->first << ", " << volume[i]->second << "]";
                throw InputError(config.path, end.line, message.str());
            }
    }
}

void requireCollisionFreeStartAndGoal(const LoadedProblem &problem, const PlanningProblem &planning)
{
    requireCollisionFreeStartAndGoal(problem, planning.setup->getSpaceInformation(), *planning.validity);
}

void requireCollisionFreeStartAndGoal(const LoadedProblem &problem, const ompl::base::SpaceInformationPtr &si,
                                      StateValidityChecker &validity)
{
    const ProblemConfig &config = problem.config;
    ompl::base::State *state = si->allocState();
    for (const bool isStart : {true, false})
    {
        const ConfigPose &pose = isStart ? config.start : config.goal;
        // The same state the planner is given, so the verdict is the one it would reach.
        configPoseToState(pose, config.planar, state);
        if (!validity.collisionFree(state))
        {
            si->freeState(state);
            const std::string which = isStart ? "start" : "goal";
            throw InputError(config.path, isStart ? config.startLine : config.goalLine,
                             "the " + which + " " + formatPose(pose, config.planar) +
                                 " collides with the environment (checker '" + validity.checker().name() +
                                 "'); no path can " + (isStart ? "leave" : "reach") + " it");
        }
    }
    si->freeState(state);
    validity.resetCounters();
}
}  // namespace hcd::cli
