// SPDX-License-Identifier: BSD-3-Clause
// The commands on scene problems (ProblemConfig::isScene()): the same command lines and outputs as
// for one robot, with every robot's pose on each line.
#pragma once

#include "hybridcd/io/path_file.h"
#include "hybridcd/io/planner_request.h"
#include "hybridcd/io/problem_scene.h"
#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/scene/scene.h"

#include <ompl/base/Planner.h>
#include <ompl/base/SpaceInformation.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace hcd::cli
{
/// The scene options of a --checker name: mesh pairs by that checker; "bruteforce" is the whole
/// reference scene (no broad phase).
SceneOptions sceneOptionsOf(const std::string &checkerName, const CheckerOptions &options);

/// Throws InputError naming the .cfg line of the start or goal when that state collides, with
/// the pair that touches.
void requireFreeEnds(const LoadedProblem &problem, const Scene &scene);

/// `check`: 1 (free) or 0 per line of robotCount poses.
int runSceneCheck(const LoadedProblem &problem, const std::string &statesPath, const std::string &checkerName,
                  const CheckerOptions &options);
/// `clearance`: the smallest distance over the checked pairs per line (0 when touching).
int runSceneClearance(const LoadedProblem &problem, const std::string &statesPath, const std::string &checkerName,
                      const CheckerOptions &options);
/// `check-motion`: 1, or 0 and the last valid fraction, per motion (two states of every robot's
/// pose); returns the index of the first motion that is not free, if any.
std::optional<std::size_t> runSceneCheckMotion(const LoadedProblem &problem,
                                               const std::vector<std::pair<PoseRecord, PoseRecord>> &motions,
                                               const std::string &checkerName, const CheckerOptions &options,
                                               bool verdictOnly);

struct SceneSolveRun
{
    double timeLimit = 10.0;
    std::string outPath;
    std::string plannerName = "rrtconnect";
    std::vector<std::pair<std::string, std::string>> params;
    std::string checkerName = "auto";
    CheckerOptions checkerOptions;
    bool continuous = true;
};
/// `solve`: plans all robots at once on the compound space and writes the path, every robot's
/// pose on each line. Returns the exit status (2 when not solved).
int runSceneSolve(const LoadedProblem &problem, const SceneSolveRun &run);
/// makePlanner on a scene's space, its refusals (an unknown planner, one that needs OMPL's informed
/// sets) naming the option: "--planner NAME: ...".
ompl::base::PlannerPtr plannerForScene(const PlannerRequest &request, const ompl::base::SpaceInformationPtr &si);
}  // namespace hcd::cli
