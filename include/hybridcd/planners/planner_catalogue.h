// SPDX-License-Identifier: BSD-3-Clause
#pragma once
#include "hybridcd/io/planner_request.h"

#include <ompl/base/Planner.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/control/SpaceInformation.h>
#include <string>
#include <utility>
#include <vector>

namespace hcd
{

/// Lowercase names of every planner the catalogue can build, sorted.
std::vector<std::string> plannerNames();

/// How rrtconnect, rrt, prm and prmstar find nearest neighbours.
enum class NeighborSearch
{
    /// PoseNearestNeighbors on SE(2) and SE(3): the neighbours OMPL's default finds, with fewer
    /// distance evaluations. Other spaces keep OMPL's default.
    Poses,
    /// OMPL's default structure (GNAT), as OMPL.app plans.
    OmplDefault,
};

/// True when the planner finds its nearest neighbours with PoseNearestNeighbors: one made by
/// makePlanner with NeighborSearch::Poses on SE(2) or SE(3) (rrtconnect and rrt once set up; prm
/// and prmstar from the start).
bool searchesWithPoseNeighbors(const ompl::base::Planner &planner);

/// "poses" or "ompl"; throws std::invalid_argument naming both for anything else.
NeighborSearch parseNeighborSearch(const std::string &name);

/// Builds the planner; applies displayName (Planner::setName) and every parameter through OMPL's ParamSet
/// (planner->params().hasParam / setParam). Throws std::invalid_argument: for an unknown type, the message lists all
/// valid names; for an unknown parameter, the message names the planner and lists that planner's valid parameter names
/// (from params().getParamNames()); for a value OMPL rejects (setParam returns false), it names the parameter and the
/// value.
/// `search` chooses the nearest-neighbour structure of rrtconnect, rrt, prm and prmstar; the others
/// ignore it.
ompl::base::PlannerPtr makePlanner(const PlannerRequest &request, const ompl::base::SpaceInformationPtr &si,
                                   NeighborSearch search = NeighborSearch::Poses);

/// The progress properties of OMPL 1.5's BIT* and ABIT* that read the planner's graph while it
/// changes it (OMPL issue 779). makePlanner leaves them out: OMPL's Benchmark reads progress from a
/// second thread, and runs died at random on them.
inline constexpr const char *kThreadUnsafeBitStarProgress[] = {"current free states INTEGER",
                                                               "current graph vertices INTEGER"};

/// Lowercase names of the control planners (for kinodynamic problems): est, kpiece, pdst, rrt, sst.
std::vector<std::string> controlPlannerNames();

/// Builds one of OMPL's control planners (ompl::control::KPIECE1, RRT, SST, EST, PDST) by
/// OMPL.app's name, with the request's name and parameters applied as makePlanner does. Throws
/// std::invalid_argument for an unknown name (listing the valid ones) or a bad parameter.
ompl::base::PlannerPtr makeControlPlanner(const PlannerRequest &request, const ompl::control::SpaceInformationPtr &si);

}  // namespace hcd
