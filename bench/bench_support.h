// SPDX-License-Identifier: BSD-3-Clause
// What the benchmark programs share: medians, and the states a sampling planner would draw.
#pragma once

#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/query/checker_registry.h"

#include <algorithm>
#include <vector>

namespace hcd::bench
{
/// Median of the values (the upper one of the middle pair for an even count).
inline double median(std::vector<double> values)
{
    std::nth_element(values.begin(), values.begin() + long(values.size() / 2), values.end());
    return values[values.size() / 2];
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
