// SPDX-License-Identifier: BSD-3-Clause
// Checks every command makes on its inputs and outputs before the real work starts, so that bad
// input fails at once with a message naming the file and line (or the option).
#pragma once

#include "command_line.h"

#include "hybridcd/io/problem_scene.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/planners/planner_catalogue.h"

#include <string>
#include <vector>

namespace hcd::cli
{
/// --neighbors (poses, the default, or ompl); a UsageError for anything else.
NeighborSearch neighborSearchOf(const CommandLine &cl);

/// Loads the problem named on the command line with the mesh limits of --max-triangles, and prints
/// the .cfg's warnings (unknown keys) on stderr; the run continues after a warning.
LoadedProblem loadProblemFor(const CommandLine &cl);

/// The files a run reads (the .cfg and its meshes): no output may replace one of them.
std::vector<std::string> inputFilesOf(const LoadedProblem &problem);

/// Throws InputError("PROBLEM.cfg:LINE: ...") naming the start or the goal when it lies outside
/// the volume the .cfg declares. (Without a declared volume the bounds grow to contain both.)
void requireStartAndGoalInVolume(const ProblemConfig &config);

/// Throws InputError("PROBLEM.cfg:LINE: ...") naming the start or the goal when it collides with
/// the environment under `planning`'s checker: no planner could succeed, and it would only find
/// out when its time is up.
void requireCollisionFreeStartAndGoal(const LoadedProblem &problem, const PlanningProblem &planning);

/// The same for the SE2/SE3 states of `si` (a control problem's pose space) under `validity`.
void requireCollisionFreeStartAndGoal(const LoadedProblem &problem, const ompl::base::SpaceInformationPtr &si,
                                      StateValidityChecker &validity);
}  // namespace hcd::cli
